// Cost of one WaypointTracker::step (polar error, gain choice, eq. 10, limits, eq. 19 check), without
// and with the actuator limits.

#include <benchmark/benchmark.h>

#include <vector>

#include "components/waypoint_controller/waypoint_tracker.hpp"

namespace {

using robodds::waypoint_controller::ControllerParams;
using robodds::waypoint_controller::WaypointTracker;

std::vector<Eigen::Vector2d> paper_mission() {
  return {{60, 20}, {75, 15}, {90, 25}, {85, 40}, {70, 45}, {60, 55}, {75, 65}, {90, 70}, {85, 85},
          {70, 90}, {55, 80}, {40, 90}, {25, 85}, {15, 70}, {25, 55}, {40, 50}, {30, 35}, {20, 20}};
}

/// Times tracker.step() at the start of the paper's mission: far from W_0, so no switch.
void step_from_mission_start(benchmark::State& state, WaypointTracker& tracker) {
  double x = 50.0;
  double y = 10.0;
  double theta = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(x);
    benchmark::DoNotOptimize(y);
    benchmark::DoNotOptimize(theta);
    benchmark::DoNotOptimize(tracker.step(x, y, theta));
  }
}

void BM_TrackerStep(benchmark::State& state) {
  ControllerParams params;
  params.max_speed_mps = 1.0;
  params.max_turn_rate_radps = 1.0;
  WaypointTracker tracker(params);
  tracker.set_mission(paper_mission());
  step_from_mission_start(state, tracker);
}
BENCHMARK(BM_TrackerStep);

// With paper1_waypoints' actuator limits (issue 12): braking bound, wheel scaling, ramp.
void BM_TrackerStepActuatorLimits(benchmark::State& state) {
  ControllerParams params;
  params.body.wheel_base_m = 0.3;
  params.body.actuator = robodds::model::ActuatorLimits{1.5, 1.0, 5.0};
  WaypointTracker tracker(params, 0.01);
  tracker.set_mission(paper_mission());
  step_from_mission_start(state, tracker);
}
BENCHMARK(BM_TrackerStepActuatorLimits);

}  // namespace

BENCHMARK_MAIN();
