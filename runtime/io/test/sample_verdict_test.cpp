// Whether a reader takes a sample (runtime/io/sample_verdict.hpp): the non-finite check before
// the type's checks, and one verdict per lockstep delivery shared by its readers. Linked with the
// system layer, which installs the content checks of its message types (as runtime_input_test).
#include "runtime/io/sample_verdict.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "robodds/idl/robodds.h"
#include "runtime/testing/sample_check_cases.hpp"

namespace robodds {
namespace {

using robodds::testing::plausible_sample;

TEST(SampleVerdict, NonFiniteNumbersFirstThenTheTypesChecks) {
  auto s = plausible_sample<idl::RobotState>();
  EXPECT_FALSE(first_failed_check(s, TimeMode::kLockstep));
  s.header().stamp_ns(-1);
  CheckResult failed = first_failed_check(s, TimeMode::kLockstep);
  ASSERT_TRUE(failed);
  EXPECT_EQ(failed->reason, check_reason::kNegativeStamp);
  EXPECT_EQ(failed->detail.substr(failed->detail.size() - 16), "[negative_stamp]") << failed->detail;
  s.y(std::numeric_limits<double>::quiet_NaN());
  failed = first_failed_check(s, TimeMode::kLockstep);
  ASSERT_TRUE(failed);
  EXPECT_EQ(failed->reason, detail::kRejectNonFinite) << "before the stamp";
  EXPECT_EQ(failed->field, "y");
}

TEST(SampleVerdict, ALockstepDeliveryIsCheckedOnceForAllItsReaders) {
  const auto good = plausible_sample<idl::RobotState>();
  auto bad = good;
  bad.x(std::numeric_limits<double>::infinity());
  bool passed = false;
  SampleMeta meta;
  meta.checks_passed = &passed;
  EXPECT_TRUE(delivery_check(bad, meta, TimeMode::kLockstep)) << "checked: refused";
  EXPECT_FALSE(passed) << "a refusal is not shared: the next reader checks again";
  EXPECT_FALSE(delivery_check(good, meta, TimeMode::kLockstep));
  EXPECT_TRUE(passed) << "the first reader's pass is shared";
  EXPECT_FALSE(delivery_check(bad, meta, TimeMode::kLockstep)) << "the next reader of this delivery trusts it";
}

TEST(SampleVerdict, RealTimeAndAloneEveryReaderChecks) {
  auto bad = plausible_sample<idl::RobotState>();
  bad.x(std::numeric_limits<double>::infinity());
  bool passed = true;  // as if another reader had passed it
  SampleMeta meta;
  meta.checks_passed = &passed;
  EXPECT_TRUE(delivery_check(bad, meta, TimeMode::kRealtime)) << "real time: stamps depend on the wall clock, no sharing";
  EXPECT_TRUE(delivery_check(bad, SampleMeta{}, TimeMode::kLockstep)) << "no shared flag: checked";
}

}  // namespace
}  // namespace robodds
