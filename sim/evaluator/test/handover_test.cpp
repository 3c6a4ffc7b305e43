#include "sim/evaluator/handover.hpp"

#include <gtest/gtest.h>

namespace robodds::evaluator {
namespace {

TEST(GapTracker, FindsTheLongestSilenceAfterStartUp) {
  GapTracker gaps(1.0);
  for (double t : {0.0, 0.9}) {  // start-up: ignored
    gaps.observe(t);
  }
  for (int i = 0; i <= 50; ++i) {  // primary at 10 Hz from 1 s to 6 s
    gaps.observe(1.0 + 0.1 * i);
  }
  gaps.observe(6.85);  // the standby's first sample
  gaps.observe(6.95);
  EXPECT_EQ(gaps.samples(), 53U);
  EXPECT_NEAR(gaps.longest().length_s, 0.85, 1e-12);
  EXPECT_NEAR(gaps.longest().from_s, 6.0, 1e-12);
  EXPECT_NEAR(gaps.longest().to_s, 6.85, 1e-12);
}

TEST(GapTracker, IgnoresReorderedSamplesAndReportsNothingBeforeTwo) {
  GapTracker gaps;
  gaps.observe(2.0);
  EXPECT_EQ(gaps.longest().length_s, 0.0);
  gaps.observe(1.0);  // older than the newest: ignored
  gaps.observe(2.5);
  EXPECT_NEAR(gaps.longest().length_s, 0.5, 1e-12);
  EXPECT_EQ(gaps.samples(), 2U);
}

}  // namespace
}  // namespace robodds::evaluator
