#pragma once
// Paper-1 way-point metrics from the recorded controller status, truth and mission.
// Pure: steps are simulation steps; distances in m; times in s.

#include <array>
#include <cstdint>
#include <vector>

#include "sim/evaluator/track.hpp"

namespace robodds::evaluator {

struct StatusSample {
  std::uint64_t step = 0;
  std::uint32_t waypoints_reached = 0;
  std::uint32_t waypoints_total = 0;
  bool done = false;
  bool switched = false;
  double switch_distance = 0.0;  // m, the controller's (estimated) distance at the switch
  double epsilon = 0.0;          // m
};

struct WaypointMetrics {
  std::uint32_t waypoints_reached = 0;
  std::uint32_t waypoints_total = 0;
  double time_to_final_s = -1.0;              // -1: the last way-point was never reached
  std::vector<double> switch_distance_estimate_m;
  std::vector<double> switch_distance_true_m;  // true distance to the reached way-point at the switch
  double final_error_true_m = 0.0;            // true distance to the last way-point at the end
  double epsilon_m = 0.0;
};

/// `mission` holds the way-points [x, y] in order; `status` and `truth` are in step order.
WaypointMetrics waypoint_metrics(const Track& truth, const std::vector<StatusSample>& status,
                                 const std::vector<std::array<double, 2>>& mission, double step_s);

}  // namespace robodds::evaluator
