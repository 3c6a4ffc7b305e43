// Closed loop with the true pose: tracker -> exact unicycle plant, dt = 0.01 s. Reproduces
// paper 1, section 4, step 2 (18 way-points from (50, 10)) and Table 1 (distance at switch for
// epsilon = 0.1 / 0.01 / 0.001). Measured figures are printed and recorded in README.md.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "common/model/actuator.hpp"
#include "common/model/diff_drive_kinematics.hpp"
#include "components/waypoint_controller/waypoint_tracker.hpp"

namespace robodds::waypoint_controller {
namespace {

constexpr double kDt = 0.01;  // s, as the reference simulation
// Alpha and sigma are judged once the robot is this close to the last way-point (m). They
// decay more slowly (time constant ~6.6 s) than d (~1 s), and below ~1e-12 m the positions
// near (20, 20) m stop resolving the motion, so the exact dynamics end there (see README.md).
constexpr double kConvergedDistanceM = 1e-9;
constexpr double kMaxSettleAfterDoneS = 60.0;

std::vector<Eigen::Vector2d> paper_mission() {
  return {{60, 20}, {75, 15}, {90, 25}, {85, 40}, {70, 45}, {60, 55}, {75, 65}, {90, 70}, {85, 85},
          {70, 90}, {55, 80}, {40, 90}, {25, 85}, {15, 70}, {25, 55}, {40, 50}, {30, 35}, {20, 20}};
}

/// The robot the loop drives: the ideal unicycle by default, or one with actuator limits
/// (each wheel clamped on its own, then the acceleration limits, as sim/plant does).
struct Robot {
  double wheel_base_m = 0.3;
  model::ActuatorLimits limits;
};

struct RunResult {
  bool done = false;
  double time_to_final_s = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> reach_distances_m;
  double max_abs_v = 0.0;
  double max_abs_omega = 0.0;
  // What the robot applied (equal to the commands for the ideal robot).
  double max_applied_wheel_mps = 0.0;
  double max_applied_accel_mps2 = 0.0;
  double max_applied_angular_accel_radps2 = 0.0;
  // The commands' own changes per step, over dt.
  double max_command_accel_mps2 = 0.0;
  double max_command_angular_accel_radps2 = 0.0;
  double max_command_wheel_mps = 0.0;
  bool converged = false;       // came within kConvergedDistanceM of the last way-point
  TrackerStatus final_status;   // at that moment (or at the end of the run)
};

RunResult run_paper_mission(const ControllerParams& params, double max_time_s, const Robot& robot = Robot{}) {
  WaypointTracker tracker(params, kDt);
  tracker.set_mission(paper_mission());
  model::Pose2 pose{50.0, 10.0, 0.0};
  model::Twist applied{};
  Command previous_command{};
  RunResult result;
  const long max_steps = std::lround(max_time_s / kDt);
  long done_step = -1;
  for (long k = 0; k <= max_steps; ++k) {
    const TrackerOutput output = tracker.step(pose.x, pose.y, pose.theta);
    result.final_status = output.status;
    result.max_abs_v = std::max(result.max_abs_v, std::abs(output.command.v));
    result.max_abs_omega = std::max(result.max_abs_omega, std::abs(output.command.omega));
    const model::WheelSpeeds cw = model::wheel_speeds_from_twist({output.command.v, output.command.omega}, robot.wheel_base_m);
    result.max_command_wheel_mps = std::max({result.max_command_wheel_mps, std::abs(cw.left), std::abs(cw.right)});
    result.max_command_accel_mps2 = std::max(result.max_command_accel_mps2, std::abs(output.command.v - previous_command.v) / kDt);
    result.max_command_angular_accel_radps2 =
        std::max(result.max_command_angular_accel_radps2, std::abs(output.command.omega - previous_command.omega) / kDt);
    previous_command = output.command;
    if (output.status.done && done_step < 0) {
      done_step = k;
    }
    if (output.status.done && output.status.distance_to_final_m <= kConvergedDistanceM) {
      result.converged = true;
      break;
    }
    if (done_step >= 0 && (k - done_step) * kDt >= kMaxSettleAfterDoneS) {
      break;
    }
    const model::Twist target = model::clamp_wheel_speeds(model::Twist{output.command.v, output.command.omega},
                                                          robot.wheel_base_m, robot.limits.max_wheel_speed_mps);
    const model::Twist next = model::limit_acceleration(target, applied, kDt, robot.limits);
    const model::WheelSpeeds w = model::wheel_speeds_from_twist(next, robot.wheel_base_m);
    result.max_applied_wheel_mps = std::max({result.max_applied_wheel_mps, std::abs(w.left), std::abs(w.right)});
    result.max_applied_accel_mps2 = std::max(result.max_applied_accel_mps2, std::abs(next.v - applied.v) / kDt);
    result.max_applied_angular_accel_radps2 =
        std::max(result.max_applied_angular_accel_radps2, std::abs(next.omega - applied.omega) / kDt);
    applied = next;
    pose = model::integrate_exact(pose, applied, kDt);
  }
  result.done = done_step >= 0;
  result.time_to_final_s = done_step * kDt;
  result.reach_distances_m = tracker.reach_distances_m();
  return result;
}

void print_figures(const char* label, double epsilon, const RunResult& run) {
  const auto [min_it, max_it] = std::minmax_element(run.reach_distances_m.begin(), run.reach_distances_m.end());
  std::printf("[table1] %s epsilon=%g reached=%zu switch distance min=%.6g max=%.6g time_to_final=%.2f s "
              "max|v|=%.3g m/s max|omega|=%.3g rad/s; at d_final=%.1e m: alpha=%.3g sigma=%.3g\n",
              label, epsilon, run.reach_distances_m.size(), *min_it, *max_it, run.time_to_final_s, run.max_abs_v,
              run.max_abs_omega, run.final_status.distance_to_final_m, run.final_status.alpha_rad,
              run.final_status.sigma_rad);
}

struct TableOneCase {
  const char* name;
  double epsilon_m;
  double min_time_s;  // plausible band around the reference time to the last way-point
  double max_time_s;  // (reference ~93.5 / 134.9 / 176.3 s)
};

void PrintTo(const TableOneCase& c, std::ostream* os) { *os << "epsilon=" << c.epsilon_m; }

class WaypointClosedLoop : public ::testing::TestWithParam<TableOneCase> {};

TEST_P(WaypointClosedLoop, ReachesAllWaypointsWithinEpsilonLikeTableOne) {
  const TableOneCase c = GetParam();
  ControllerParams params;
  params.stop_when_done = false;  // the paper: the law stays active on the last way-point
  params.epsilon_m = c.epsilon_m;
  const RunResult run = run_paper_mission(params, 400.0);
  ASSERT_TRUE(run.done);
  ASSERT_EQ(run.reach_distances_m.size(), 18u);
  print_figures("unlimited", c.epsilon_m, run);
  // The time-step bound: the command v = kd·d is held over a step, so going straight at the
  // way-point d shrinks by the factor (1 - kd·dt) per step (by less when alpha != 0): the first
  // step within epsilon is at a distance in ((1 - kd·dt)·epsilon, epsilon]. A tracker that
  // switches a step late, or measures after moving, lands below it.
  const double lower = (1.0 - params.forward_gains.kd * kDt) * c.epsilon_m;
  for (const double distance : run.reach_distances_m) {
    EXPECT_LE(distance, c.epsilon_m);
    EXPECT_GT(distance, lower);
  }
  EXPECT_GT(run.time_to_final_s, c.min_time_s);
  EXPECT_LT(run.time_to_final_s, c.max_time_s);
  // The law converges onto the last way-point with alpha -> 0 and sigma -> 0 (heading pi/2);
  // a wrong sign of sigma still reaches every way-point but keeps |sigma| ~ 2.5-3 rad here.
  ASSERT_TRUE(run.converged);
  EXPECT_LT(std::abs(run.final_status.alpha_rad), 0.03);
  EXPECT_LT(std::abs(run.final_status.sigma_rad), 0.2);
}

INSTANTIATE_TEST_SUITE_P(TableOne, WaypointClosedLoop,
                         ::testing::Values(TableOneCase{"epsilon_0p1", 0.1, 70.0, 130.0},
                                           TableOneCase{"epsilon_0p01", 0.01, 105.0, 170.0},
                                           TableOneCase{"epsilon_0p001", 0.001, 140.0, 215.0}),
                         [](const ::testing::TestParamInfo<TableOneCase>& info) { return std::string(info.param.name); });

TEST(WaypointClosedLoopLimited, StillReachesAllWaypointsWithUnitLimits) {
  ControllerParams params;
  params.stop_when_done = false;  // the paper: the law stays active on the last way-point
  params.epsilon_m = 0.1;
  params.max_speed_mps = 1.0;
  params.max_turn_rate_radps = 1.0;
  const RunResult run = run_paper_mission(params, 1500.0);
  ASSERT_TRUE(run.done);
  ASSERT_EQ(run.reach_distances_m.size(), 18u);
  print_figures("|v|<=1,|omega|<=1", params.epsilon_m, run);
  for (const double distance : run.reach_distances_m) {
    EXPECT_LE(distance, params.epsilon_m);
  }
  EXPECT_LE(run.max_abs_v, 1.0);
  EXPECT_LE(run.max_abs_omega, 1.0);
  EXPECT_GT(run.time_to_final_s, 130.0);  // slower than the unlimited ~93.5 s
  ASSERT_TRUE(run.converged);
  EXPECT_LT(std::abs(run.final_status.alpha_rad), 0.03);
  EXPECT_LT(std::abs(run.final_status.sigma_rad), 0.2);
}

// Issue 12: a robot with a 0.3 m track, wheels at most 1.5 m/s, 1 m/s^2 and 5 rad/s^2.
model::ActuatorLimits realistic_limits() { return model::ActuatorLimits{1.5, 1.0, 5.0}; }

void print_limited(const char* label, const RunResult& run) {
  std::printf("[limits] %s reached=%zu/18 time_to_final=%.2f s max wheel applied=%.4g commanded=%.4g m/s; "
              "max |dv/dt| applied=%.4g commanded=%.4g m/s^2; max |domega/dt| applied=%.4g commanded=%.4g rad/s^2\n",
              label, run.reach_distances_m.size(), run.time_to_final_s, run.max_applied_wheel_mps,
              run.max_command_wheel_mps, run.max_applied_accel_mps2, run.max_command_accel_mps2,
              run.max_applied_angular_accel_radps2, run.max_command_angular_accel_radps2);
}

// The controller knows the limits: it scales v and omega together (same curvature) and ramps its
// commands, so the robot follows them exactly and still reaches every way-point.
TEST(WaypointClosedLoopActuator, ReachesAllWaypointsWhenTheControllerKnowsTheLimits) {
  ControllerParams params;
  params.body.wheel_base_m = 0.3;
  params.body.actuator = realistic_limits();
  const Robot robot{0.3, realistic_limits()};
  const RunResult run = run_paper_mission(params, 600.0, robot);
  print_limited("controller aware", run);
  ASSERT_TRUE(run.done);
  EXPECT_EQ(run.reach_distances_m.size(), 18u);
  for (const double distance : run.reach_distances_m) {
    EXPECT_LE(distance, params.epsilon_m);
  }
  constexpr double kTolerance = 1e-9;
  EXPECT_LE(run.max_command_wheel_mps, 1.5 + kTolerance) << "the commands are within the wheel limit";
  EXPECT_LE(run.max_command_accel_mps2, 1.0 + kTolerance);
  EXPECT_LE(run.max_command_angular_accel_radps2, 5.0 + kTolerance);
  EXPECT_LE(run.max_applied_wheel_mps, 1.5 + kTolerance);
  EXPECT_LE(run.max_applied_accel_mps2, 1.0 + kTolerance);
  EXPECT_LE(run.max_applied_angular_accel_radps2, 5.0 + kTolerance);
  EXPECT_GT(run.time_to_final_s, 200.0) << "a robot at 1.5 m/s is much slower than the unlimited ~93.5 s";
}

// The same robot driven by a controller that ignores the limits (issue 12: "the robot shuttles
// back and forth and reaches 0 of 18"): the wheel clamp bends the commanded arcs.
TEST(WaypointClosedLoopActuator, AnUnawareControllerFailsOnTheSameRobot) {
  ControllerParams params;  // no actuator limits
  const Robot robot{0.3, realistic_limits()};
  const RunResult run = run_paper_mission(params, 600.0, robot);
  print_limited("controller unaware", run);
  EXPECT_LT(run.reach_distances_m.size(), 18u);
  EXPECT_GT(run.max_command_wheel_mps, 1.5) << "it commands what the wheels cannot do";
  EXPECT_LE(run.max_applied_wheel_mps, 1.5 + 1e-9) << "and the robot does not do it";
}

}  // namespace
}  // namespace robodds::waypoint_controller
