#include "sim/evaluator/waypoint_metrics.hpp"

#include <gtest/gtest.h>

namespace robodds::evaluator {
namespace {

TEST(WaypointMetrics, SwitchDistancesTimesAndFinalError) {
  const std::vector<std::array<double, 2>> mission{{1.0, 0.0}, {2.0, 0.0}};
  const Track truth{{0, 0.0, 0, 0}, {10, 0.95, 0, 0}, {20, 1.97, 0, 0}, {30, 1.99, 0, 0}};
  std::vector<StatusSample> status(4);
  status[0] = {0, 0, 2, false, false, 0.0, 0.1};
  status[1] = {10, 1, 2, false, true, 0.04, 0.1};  // estimate said 0.04, truth is 0.05 away
  status[2] = {20, 2, 2, true, true, 0.02, 0.1};
  status[3] = {30, 2, 2, true, false, 0.0, 0.1};
  const WaypointMetrics m = waypoint_metrics(truth, status, mission, 0.01);
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

TEST(WaypointMetrics, NeverDoneMeansNoTimeToFinal) {
  const WaypointMetrics m = waypoint_metrics({{0, 0, 0, 0}}, {{0, 0, 3, false, false, 0, 0.1}}, {{5, 5}}, 0.01);
  EXPECT_LT(m.time_to_final_s, 0.0);
  EXPECT_EQ(m.waypoints_reached, 0u);
}

}  // namespace
}  // namespace robodds::evaluator
