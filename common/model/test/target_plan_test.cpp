#include "common/model/target_plan.hpp"

#include <gtest/gtest.h>

namespace robodds::model {
namespace {

// The paper-2 mission: four robots on target 1, at 1000 s robots 1-3 move to target 2 and 4 leaves.
TargetPlan paper_plan() {
  TargetPlan plan;
  plan.targets = {{1, 1000.0, 1000.0, 200.0}, {2, 2000.0, 2000.0, 150.0}};
  plan.events = {{0.0, {1, 2, 3, 4}, false, 1}, {1000.0, {1, 2, 3}, false, 2}, {1000.0, {4}, true, 0}};
  return plan;
}

TEST(TargetPlan, TasksFollowTheEventsInOrder) {
  const TargetPlan plan = paper_plan();
  const std::vector<std::uint32_t> robots{1, 2, 3, 4};
  auto before = plan.tasks_at(49999, 0.02, robots);
  EXPECT_TRUE(before.at(4).active);
  EXPECT_EQ(before.at(3).target_id, 1u);
  EXPECT_EQ(before.at(3).slot, 2u);
  EXPECT_EQ(before.at(3).team_size, 4u);
  EXPECT_DOUBLE_EQ(before.at(1).radius_m, 200.0);
  auto after = plan.tasks_at(50000, 0.02, robots);  // 1000 s at 0.02 s
  EXPECT_FALSE(after.at(4).active);
  EXPECT_EQ(after.at(4).team_size, 0u);
  EXPECT_EQ(after.at(1).target_id, 2u);
  EXPECT_DOUBLE_EQ(after.at(1).target_x, 2000.0);
  EXPECT_DOUBLE_EQ(after.at(2).radius_m, 150.0);
  EXPECT_EQ(after.at(3).team_size, 3u);
  EXPECT_EQ(after.at(3).slot, 2u);
}

TEST(TargetPlan, RobotsWithoutAnEventHaveNoTask) {
  TargetPlan plan = paper_plan();
  plan.events[0].time_s = 10.0;
  const auto tasks = plan.tasks_at(0, 0.02, {1, 7});
  EXPECT_FALSE(tasks.at(1).active);  // its first event is at step 500
  EXPECT_FALSE(tasks.at(7).active);  // in no event
  EXPECT_EQ(tasks.count(2), 0u);     // not asked for
}

TEST(TargetPlan, ChangeStepsAreSortedAndUnique) {
  const TargetPlan plan = paper_plan();
  EXPECT_EQ(plan.change_steps(0.02), (std::vector<std::uint64_t>{0, 50000}));
  EXPECT_EQ(TargetPlan::event_step(0.03, 0.02), 2u);  // rounded to the nearest step
  EXPECT_TRUE(TargetPlan{}.empty());
}

}  // namespace
}  // namespace robodds::model
