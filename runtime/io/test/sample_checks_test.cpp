// Header checks, the runtime's own bookkeeping types and the content-check slot
// (runtime/io/sample_checks.hpp), without an Input. This test does not link the system layer:
// its message types have no content check here.
#include "runtime/io/sample_checks.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "runtime/testing/sample_check_cases.hpp"

namespace robodds {
namespace {

using robodds::testing::check_reason_of;
using robodds::testing::plausible_sample;
constexpr std::int64_t kNow = robodds::testing::kCheckNowNs;

TEST(SampleChecks, HeaderStampsAndSteps) {
  auto s = plausible_sample<idl::StepDone>();
  EXPECT_EQ(check_reason_of(s, TimeMode::kRealtime), "ok");
  s.header().stamp_ns(std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(check_reason_of(s, TimeMode::kRealtime), "stamp_in_future:header.stamp_ns");
  EXPECT_EQ(check_reason_of(s, TimeMode::kLockstep), "ok") << "lockstep stamps are sim time";
  s.header().stamp_ns(kNow + sample_bounds::kFutureStampToleranceNs);
  EXPECT_EQ(check_reason_of(s, TimeMode::kRealtime), "ok") << "at the tolerance";
  s.header().stamp_ns(kNow + sample_bounds::kFutureStampToleranceNs + 1);
  EXPECT_EQ(check_reason_of(s, TimeMode::kRealtime), "stamp_in_future:header.stamp_ns");
  for (std::int64_t bad : {std::numeric_limits<std::int64_t>::min(), std::int64_t{-1}}) {
    s.header().stamp_ns(bad);
    EXPECT_EQ(check_reason_of(s, TimeMode::kRealtime), "negative_stamp:header.stamp_ns");
    EXPECT_EQ(check_reason_of(s, TimeMode::kLockstep), "negative_stamp:header.stamp_ns");
  }
  s.header().stamp_ns(0);
  s.header().next_step(2);  // before step 3
  EXPECT_EQ(check_reason_of(s), "bad_header:header.next_step");
  s.header().next_step(std::numeric_limits<std::uint64_t>::max());  // never again: fine
  EXPECT_EQ(check_reason_of(s), "ok");
}

TEST(SampleChecks, RuntimeTopics) {
  auto t = plausible_sample<idl::SimTick>();
  t.step_s(0.01);
  EXPECT_EQ(check_reason_of(t), "ok");
  t.step_s(-0.01);
  EXPECT_EQ(check_reason_of(t), "negative_duration:step_s");
  EXPECT_EQ(check_reason_of(plausible_sample<idl::StepDone>()), "ok");
  EXPECT_EQ(check_reason_of(plausible_sample<idl::HostAlive>()), "ok");

  auto r = plausible_sample<idl::HostReport>();
  r.ticks(10);
  r.late_steps(10);
  r.worst_lateness_s(0.02);
  EXPECT_EQ(check_reason_of(r), "ok");
  r.late_steps(11);
  EXPECT_EQ(check_reason_of(r), "bad_size:late_steps");
  r.late_steps(0);
  r.worst_lateness_s(-1.0);
  EXPECT_EQ(check_reason_of(r), "negative_duration:worst_lateness_s");
}

TEST(SampleChecks, TypeWithoutContentCheckIsRefusedNamingTopicAndType) {
  try {
    require_content_check<idl::RobotState>("plant/state");
    FAIL() << "a type without content check was accepted";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("topic plant/state"), std::string::npos) << what;
    EXPECT_NE(what.find("robodds::idl::RobotState"), std::string::npos) << what;
  }
  EXPECT_THROW(check_sample(plausible_sample<idl::RobotState>(), TimeMode::kLockstep, kNow), ConfigError);
}

TEST(SampleChecks, InstalledContentCheckRuns) {
  set_content_check<idl::Odometry>([](const idl::Odometry& o) { return field_check::duration("dt_s", o.dt_s()); });
  auto o = plausible_sample<idl::Odometry>();
  EXPECT_EQ(check_reason_of(o), "ok");
  o.dt_s(-1.0);
  EXPECT_EQ(check_reason_of(o), "negative_duration:dt_s");
  set_content_check<idl::Odometry>(nullptr);
}

}  // namespace
}  // namespace robodds
