#include "runtime/health/overrun_counter.hpp"

#include <gtest/gtest.h>

namespace robodds {
namespace {

constexpr double kStep = 0.01;

TEST(OverrunCounter, OnTimeStepsCountNothing) {
  OverrunCounter c(kStep, 0);
  for (std::uint64_t s = 0; s < 100; ++s) {
    EXPECT_FALSE(c.ran(s, s, 0, static_cast<double>(s) * kStep + 0.001));
  }
  EXPECT_EQ(c.figures().ticks, 100u);
  EXPECT_EQ(c.figures().missed_steps, 0u);
  EXPECT_EQ(c.figures().late_steps, 0u);
  EXPECT_DOUBLE_EQ(c.figures().worst_lateness_s, 0.0);
  EXPECT_FALSE(c.exceeded());
}

TEST(OverrunCounter, CountsSkippedStepsAndWorstLateness) {
  OverrunCounter c(kStep, 2);
  EXPECT_FALSE(c.ran(0, 0, 0, 0.0));
  // Step 1 was due at 0.01 s; the loop got there at 0.043 s: steps 1..3 skipped, ran step 4.
  EXPECT_TRUE(c.ran(1, 4, 3, 0.043));
  EXPECT_EQ(c.figures().missed_steps, 3u);
  EXPECT_EQ(c.figures().late_steps, 1u);
  EXPECT_NEAR(c.figures().worst_lateness_s, 0.033, 1e-12);
  EXPECT_TRUE(c.exceeded());  // 3 > 2
  EXPECT_FALSE(c.ran(5, 5, 0, 0.0502));
  EXPECT_NEAR(c.figures().worst_lateness_s, 0.033, 1e-12);  // the worst, not the newest
}

TEST(OverrunCounter, LateWithoutSkippingIsCountedButNotWarned) {
  OverrunCounter c(kStep, 0);
  EXPECT_FALSE(c.ran(3, 3, 0, 0.038));  // 8 ms late, more than half a step
  EXPECT_EQ(c.figures().late_steps, 1u);
  EXPECT_EQ(c.figures().missed_steps, 0u);
  EXPECT_NEAR(c.figures().worst_lateness_s, 0.008, 1e-12);
  EXPECT_FALSE(c.exceeded());
}

TEST(OverrunCounter, WarnsFirstThenEveryTenSeconds) {
  OverrunCounter c(kStep, 1000000);
  EXPECT_TRUE(c.ran(10, 12, 2, 0.125));
  EXPECT_FALSE(c.ran(20, 22, 2, 0.225));
  EXPECT_FALSE(c.ran(900, 902, 2, 9.025));
  EXPECT_TRUE(c.ran(1015, 1017, 2, 10.175));  // 10 s after the first warning
  EXPECT_FALSE(c.ran(1020, 1022, 2, 10.225));
  EXPECT_EQ(c.figures().missed_steps, 10u);
  EXPECT_NE(c.totals_text().find("skipped 10 due steps in all"), std::string::npos) << c.totals_text();
}

TEST(OverrunCounter, StepsNotRunBeforeTheEndAreMissed) {
  OverrunCounter c(kStep, 0);
  c.missed_at_end(4);
  EXPECT_EQ(c.figures().missed_steps, 4u);
  EXPECT_TRUE(c.exceeded());
}

TEST(DueStepsBetween, UnionOfThePeriods) {
  EXPECT_EQ(due_steps_between({1}, 3, 10), 7u);
  EXPECT_EQ(due_steps_between({10}, 1, 30), 2u);      // 10, 20
  EXPECT_EQ(due_steps_between({10, 4}, 1, 21), 6u);   // 4 8 10 12 16 20
  EXPECT_EQ(due_steps_between({5, 1}, 0, 3), 3u);
  EXPECT_EQ(due_steps_between({5}, 10, 10), 0u);
  EXPECT_EQ(due_steps_between({}, 0, 10), 0u);
}

TEST(DefaultMaxMissedSteps, FivePercentRoundedDown) {
  EXPECT_EQ(default_max_missed_steps(1001), 50u);
  EXPECT_EQ(default_max_missed_steps(19), 0u);
  EXPECT_EQ(default_max_missed_steps(20001), 1000u);
}

}  // namespace
}  // namespace robodds
