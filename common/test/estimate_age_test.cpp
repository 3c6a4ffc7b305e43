// Issue 24, finding 5: an estimate older than two of its producer's periods is late (hold the
// last command, never raise it), older than the timeout stale (zero).
#include "common/estimate_age.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace robodds::control {
namespace {

TEST(EstimateAge, FreshUpToTwoProducerPeriodsThenLateThenStale) {
  const double period_s = 0.01;  // a 100 Hz estimator
  const double timeout_s = 0.5;
  EXPECT_EQ(classify_estimate_age(0.0, period_s, timeout_s), EstimateAge::kFresh);
  EXPECT_EQ(classify_estimate_age(0.02, period_s, timeout_s), EstimateAge::kFresh) << "one sample a little late";
  EXPECT_EQ(classify_estimate_age(0.021, period_s, timeout_s), EstimateAge::kLate);
  EXPECT_EQ(classify_estimate_age(0.5, period_s, timeout_s), EstimateAge::kLate);
  EXPECT_EQ(classify_estimate_age(0.501, period_s, timeout_s), EstimateAge::kStale);
  EXPECT_EQ(classify_estimate_age(std::nan(""), period_s, timeout_s), EstimateAge::kStale);
}

TEST(EstimateAge, AnUnknownPeriodMakesEveryAgedEstimateLate) {
  EXPECT_EQ(classify_estimate_age(0.0, 0.0, 0.5), EstimateAge::kFresh);
  EXPECT_EQ(classify_estimate_age(0.001, 0.0, 0.5), EstimateAge::kLate);
  EXPECT_EQ(classify_estimate_age(0.001, std::numeric_limits<double>::infinity(), 0.5), EstimateAge::kLate);
}

TEST(EstimateAge, TheProducersPeriodIsWhatItsHeaderAnnounces) {
  EXPECT_DOUBLE_EQ(producer_period_s(40, 50, 0.01), 0.1) << "a 10 Hz producer on 0.01 s steps";
  EXPECT_DOUBLE_EQ(producer_period_s(40, 40, 0.01), 0.0);
  EXPECT_DOUBLE_EQ(producer_period_s(40, std::numeric_limits<std::uint64_t>::max(), 0.01), 0.0) << "its last sample";
}

TEST(LateEstimateWatch, SaysLateOnceAndKeepsJudging) {
  LateEstimateWatch watch;
  std::string warning;
  EXPECT_FALSE(watch.late(0.015, 10, 11, 0.01, 0.5, warning)) << "within two periods of 0.01 s";
  EXPECT_TRUE(warning.empty());
  EXPECT_TRUE(watch.late(0.06, 10, 11, 0.01, 0.5, warning));
  EXPECT_NE(warning.find("0.06 s old (> 2 periods of 0.01 s)"), std::string::npos) << warning;
  warning.clear();
  EXPECT_TRUE(watch.late(0.07, 10, 11, 0.01, 0.5, warning));
  EXPECT_TRUE(warning.empty()) << "said once";
  EXPECT_FALSE(watch.late(0.6, 10, 11, 0.01, 0.5, warning)) << "stale, not late";
}

}  // namespace
}  // namespace robodds::control
