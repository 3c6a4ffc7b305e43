#include "sim/evaluator/metrics/waypoints/waypoint_metrics.hpp"

#include <gtest/gtest.h>

namespace robodds::evaluator {
namespace {

TEST(WaypointTracker, SwitchDistancesTimesAndFinalError) {
  WaypointTracker tracker;
  tracker.set_mission({{1.0, 0.0}, {2.0, 0.0}});
  TruthWindow truth;
  const std::vector<PoseSample> poses{{0, 0.0, 0, 0}, {10, 0.95, 0, 0}, {20, 1.97, 0, 0}, {30, 1.99, 0, 0}};
  const std::vector<StatusSample> status{{0, 0, 2, false, false, 0.0, 0.1},
                                         {10, 1, 2, false, true, 0.04, 0.1},  // estimate said 0.04, truth is 0.05 away
                                         {20, 2, 2, true, true, 0.02, 0.1},
                                         {30, 2, 2, true, false, 0.0, 0.1}};
  for (std::size_t i = 0; i < poses.size(); ++i) {
    tracker.add_status(status[i]);  // before the truth of its step
    tracker.match(truth);
    truth.add(poses[i]);
    tracker.match(truth);
  }
  const WaypointMetrics m = tracker.metrics(&poses.back(), 0.01);
  EXPECT_EQ(m.waypoints_reached, 2u);
  EXPECT_EQ(m.waypoints_total, 2u);
  EXPECT_DOUBLE_EQ(m.time_to_final_s, 0.2);
  ASSERT_EQ(m.switch_distance_estimate_m.size(), 2u);
  EXPECT_DOUBLE_EQ(m.switch_distance_estimate_m[0], 0.04);
  ASSERT_EQ(m.switch_distance_true_m.size(), 2u);
  EXPECT_NEAR(m.switch_distance_true_m[0], 0.05, 1e-12);
  EXPECT_NEAR(m.switch_distance_true_m[1], 0.03, 1e-12);
  EXPECT_NEAR(m.final_error_true_m, 0.01, 1e-12);
  EXPECT_DOUBLE_EQ(m.epsilon_m, 0.1);
}

TEST(WaypointTracker, NeverDoneMeansNoTimeToFinal) {
  WaypointTracker tracker;
  tracker.set_mission({{5, 5}});
  tracker.add_status({0, 0, 3, false, false, 0, 0.1});
  const PoseSample last{0, 0, 0, 0};
  const WaypointMetrics m = tracker.metrics(&last, 0.01);
  EXPECT_LT(m.time_to_final_s, 0.0);
  EXPECT_EQ(m.waypoints_reached, 0u);
  EXPECT_TRUE(tracker.has_status());
  EXPECT_TRUE(tracker.has_mission());
}

TEST(WaypointTracker, ASwitchWithoutTruthAtItsStepHasNoTrueDistance) {
  WaypointTracker tracker;
  tracker.set_mission({{1.0, 0.0}});
  TruthWindow truth;
  truth.add({0, 0, 0, 0});
  tracker.add_status({5, 1, 1, true, true, 0.02, 0.1});
  tracker.match(truth);
  EXPECT_EQ(tracker.needed_from(), 5u) << "waits for the truth of step 5";
  truth.add({6, 0, 0, 0});
  tracker.match(truth);
  const WaypointMetrics m = tracker.metrics(nullptr, 0.01);
  EXPECT_EQ(m.switch_distance_estimate_m.size(), 1u);
  EXPECT_TRUE(m.switch_distance_true_m.empty());
  EXPECT_DOUBLE_EQ(m.final_error_true_m, 0.0);
}

}  // namespace
}  // namespace robodds::evaluator
