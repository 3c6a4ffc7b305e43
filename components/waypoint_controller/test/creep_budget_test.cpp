// Issue 24, finding 3: creeping without a valid estimate only before the first valid one, never
// once the mission is done, within a commanded distance and a time.
#include "components/waypoint_controller/creep_budget.hpp"

#include <gtest/gtest.h>

namespace robodds::waypoint_controller {
namespace {

constexpr double kPeriodS = 0.01;  // s, 100 Hz

TEST(CreepBudget, AllowsCreepingBeforeTheFirstValidEstimateOnly) {
  CreepBudget creep(CreepLimits{2.0, 10.0});
  EXPECT_EQ(creep.check(0.0, false), CreepVerdict::kAllowed);
  creep.crept(0.3, kPeriodS);
  creep.estimate_was_valid();
  EXPECT_EQ(creep.check(0.01, false), CreepVerdict::kAfterValidEstimate) << "the estimate was valid once: never again";
  EXPECT_EQ(creep.check(100.0, false), CreepVerdict::kAfterValidEstimate);
}

TEST(CreepBudget, NeverCreepsOnceTheMissionIsDone) {
  CreepBudget creep(CreepLimits{2.0, 10.0});
  EXPECT_EQ(creep.check(0.0, true), CreepVerdict::kMissionDone);
}

TEST(CreepBudget, StopsAtTheCommandedDistance) {
  CreepBudget creep(CreepLimits{1.999, 1000.0});  // the last step passes it by < one step
  double time_s = 0.0;
  int steps = 0;
  while (creep.check(time_s, false) == CreepVerdict::kAllowed && steps < 100000) {
    creep.crept(-0.5, kPeriodS);  // backing up counts as well
    time_s += kPeriodS;
    ++steps;
  }
  EXPECT_EQ(creep.check(time_s, false), CreepVerdict::kDistanceSpent);
  EXPECT_EQ(steps, 400) << "2 m at 0.5 m/s: 4 s of 0.01 s steps";
  EXPECT_NEAR(creep.distance_m(), 2.0, 1e-9);
}

TEST(CreepBudget, StopsAfterItsTimeFromTheFirstCreepingStep) {
  CreepBudget creep(CreepLimits{1000.0, 10.0});
  EXPECT_EQ(creep.check(5.0, false), CreepVerdict::kAllowed) << "the time counts from here";
  creep.crept(0.3, kPeriodS);
  EXPECT_EQ(creep.check(15.0, false), CreepVerdict::kAllowed) << "10 s after the first creeping step";
  EXPECT_EQ(creep.check(15.02, false), CreepVerdict::kTimeSpent);
}

TEST(CreepBudget, AnEstimatorRestartGrantsANewBudgetUntilTheAllowanceIsUsedUp) {
  CreepBudget creep(CreepLimits{2.0, 10.0, 2});
  creep.crept(0.3, kPeriodS);
  creep.estimate_was_valid();
  EXPECT_EQ(creep.check(1.0, false), CreepVerdict::kAfterValidEstimate);
  ASSERT_TRUE(creep.estimator_restarted());
  EXPECT_EQ(creep.distance_m(), 0.0) << "a new budget";
  EXPECT_EQ(creep.check(50.0, false), CreepVerdict::kAllowed) << "its time counts from here";
  EXPECT_EQ(creep.check(60.0, false), CreepVerdict::kAllowed);
  EXPECT_EQ(creep.check(60.02, false), CreepVerdict::kTimeSpent);
  EXPECT_EQ(creep.check(70.0, true), CreepVerdict::kMissionDone) << "never once the mission is done";
  creep.estimate_was_valid();
  ASSERT_TRUE(creep.estimator_restarted());
  creep.estimate_was_valid();
  EXPECT_FALSE(creep.estimator_restarted()) << "max_restarts 2 used up";
  EXPECT_EQ(creep.check(80.0, false), CreepVerdict::kAfterValidEstimate);
}

TEST(CreepBudget, NoRestartBudgetWhenNoneIsAllowed) {
  CreepBudget creep(CreepLimits{2.0, 10.0, 0});
  creep.estimate_was_valid();
  EXPECT_FALSE(creep.estimator_restarted());
  EXPECT_EQ(creep.check(1.0, false), CreepVerdict::kAfterValidEstimate);
}

}  // namespace
}  // namespace robodds::waypoint_controller
