// The path-following law (issue 28, path_law.hpp): its geometry, its raw law, and in closed loop
// with the true pose on the limited robot of paper1_long_leg (0.3 m track, 1.5 m/s wheels,
// 1 m/s^2, 5 rad/s^2): straight legs where the paper's law strays tens of metres sideways.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "common/angle.hpp"
#include "common/model/actuator.hpp"
#include "common/model/diff_drive_kinematics.hpp"
#include "components/waypoint_controller/path_law.hpp"
#include "components/waypoint_controller/waypoint_tracker.hpp"

namespace robodds::waypoint_controller {
namespace {

constexpr double kDt = 0.01;  // s

TEST(PathError, CrossTrackIsSignedLeftPositiveAndAlongTrackFromTheStart) {
  const PathError left = path_error({0, 0}, {100, 0}, {30, 2}, 0.0, 5.0);
  EXPECT_DOUBLE_EQ(left.cross_track_m, 2.0);
  EXPECT_DOUBLE_EQ(left.along_track_m, 30.0);
  EXPECT_NEAR(left.distance_m, std::hypot(70.0, 2.0), 1e-12);
  // Aims 5 m ahead on the leg: (35, 0), i.e. down and forward.
  EXPECT_NEAR(left.desired_heading_rad, std::atan2(-2.0, 5.0), 1e-12);
  EXPECT_NEAR(left.heading_error_rad, std::atan2(-2.0, 5.0), 1e-12);

  const PathError right = path_error({0, 0}, {0, 100}, {3, 10}, kPi / 2, 5.0);  // a northward leg
  EXPECT_DOUBLE_EQ(right.cross_track_m, -3.0);
  EXPECT_DOUBLE_EQ(right.along_track_m, 10.0);
  EXPECT_NEAR(right.heading_error_rad, std::atan2(5.0, -3.0) - kPi / 2, 1e-12);
}

TEST(PathError, AimsAtTheWaypointOnceTheLookaheadPointWouldPassIt) {
  const PathError near_end = path_error({0, 0}, {100, 0}, {97, 1}, 0.0, 5.0);
  EXPECT_NEAR(near_end.desired_heading_rad, std::atan2(-1.0, 3.0), 1e-12);
  const PathError overshot = path_error({0, 0}, {100, 0}, {101, 0.5}, 0.0, 5.0);
  EXPECT_NEAR(std::abs(overshot.desired_heading_rad), kPi - std::atan2(0.5, 1.0), 1e-12);  // back to it
}

TEST(PathError, BeforeTheStartItAimsAtTheLegsStart) {
  const PathError behind = path_error({0, 0}, {100, 0}, {-20, 0.0}, 0.0, 5.0);
  EXPECT_NEAR(behind.desired_heading_rad, 0.0, 1e-12);  // towards (0, 0), not 5 m past it
  EXPECT_DOUBLE_EQ(behind.along_track_m, -20.0);
}

TEST(PathError, ALegWithoutLengthAimsAtTheWaypoint) {
  const PathError degenerate = path_error({10, 10}, {10, 10}, {0, 0}, 0.0, 5.0);
  EXPECT_DOUBLE_EQ(degenerate.cross_track_m, 0.0);
  EXPECT_NEAR(degenerate.desired_heading_rad, kPi / 4, 1e-12);
  const PathError on_it = path_error({10, 10}, {10, 10}, {10, 10}, 0.3, 5.0);
  EXPECT_DOUBLE_EQ(on_it.heading_error_rad, 0.0);  // no direction at all: keep the heading
}

TEST(PathLaw, DrivesByDistanceSlowedByTheHeadingErrorAndNeverBacksUp) {
  const GainSet gains{1.0, 20.0, -2.5};
  PathError error;
  error.distance_m = 10.0;
  error.heading_error_rad = 0.5;
  Command c = path_law(error, gains);
  EXPECT_NEAR(c.v, 10.0 * std::cos(0.5), 1e-12);
  EXPECT_NEAR(c.omega, 10.0, 1e-12);
  error.heading_error_rad = -2.0;  // facing away: turn on the spot
  c = path_law(error, gains);
  EXPECT_DOUBLE_EQ(c.v, 0.0);
  EXPECT_NEAR(c.omega, -40.0, 1e-12);
}

/// Closed loop with the true pose on the limited robot; the cross-track error of every step
/// after the first `settle_m` metres of each leg, against the leg the mission defines (for the
/// first leg: from the start position).
struct LegRun {
  bool done = false;
  double time_to_final_s = 0.0;
  double cross_track_rms_m = 0.0;
  double cross_track_max_m = 0.0;
};

void print(const char* label, const LegRun& run) {
  std::printf("[%s] done=%d time_to_final=%.2f s cross-track rms=%.4f m max=%.4f m\n", label, run.done ? 1 : 0,
              run.time_to_final_s, run.cross_track_rms_m, run.cross_track_max_m);
}

LegRun drive(const std::vector<Eigen::Vector2d>& mission, const model::Pose2& start, double lookahead_m,
             double max_time_s, double settle_m = 10.0) {
  ControllerParams params;
  params.body.wheel_base_m = 0.3;
  params.body.actuator = model::ActuatorLimits{1.5, 1.0, 5.0};
  params.path_lookahead_m = lookahead_m;
  WaypointTracker tracker(params, kDt);
  tracker.set_mission(mission);
  model::Pose2 pose = start;
  model::Twist applied{};
  LegRun run;
  double sum_squares = 0.0;
  long samples = 0;
  const long steps = std::lround(max_time_s / kDt);
  for (long k = 0; k <= steps && !run.done; ++k) {
    const std::size_t leg = tracker.target_index();
    const Eigen::Vector2d from = leg == 0 ? Eigen::Vector2d(start.x, start.y) : mission[leg - 1];
    const PathError e = path_error(from, mission[leg], {pose.x, pose.y}, pose.theta, 1.0);
    if (e.along_track_m > settle_m) {
      sum_squares += e.cross_track_m * e.cross_track_m;
      run.cross_track_max_m = std::max(run.cross_track_max_m, std::abs(e.cross_track_m));
      ++samples;
    }
    const TrackerOutput out = tracker.step(pose.x, pose.y, pose.theta);
    if (out.status.done) {
      run.done = true;
      run.time_to_final_s = k * kDt;
    }
    const model::Twist target = model::clamp_wheel_speeds(model::Twist{out.command.v, out.command.omega}, 0.3, 1.5);
    applied = model::limit_acceleration(target, applied, kDt, params.body.actuator);
    pose = model::integrate_exact(pose, applied, kDt);
  }
  run.cross_track_rms_m = samples > 0 ? std::sqrt(sum_squares / samples) : 0.0;
  return run;
}

TEST(PathLawClosedLoop, TheLongLegStaysStraightWhereThePapersLawStraysSideways) {
  const std::vector<Eigen::Vector2d> leg{{550, 10}};  // sim/scenarios/paper1_long_leg.yaml
  const model::Pose2 start{50.0, 10.0, 0.0};
  const LegRun paper = drive(leg, start, 0.0, 450.0);
  const LegRun path = drive(leg, start, 3.0, 450.0);
  print("long leg, paper", paper);
  print("long leg, path 3 m", path);
  ASSERT_TRUE(paper.done);
  ASSERT_TRUE(path.done);
  EXPECT_GT(paper.cross_track_max_m, 10.0);  // the ksigma term pulls the heading north
  EXPECT_LT(path.cross_track_max_m, 0.05);
  EXPECT_LE(path.time_to_final_s, paper.time_to_final_s);
}

TEST(PathLawClosedLoop, FiveLegsOf300mHoldTheirLinesAfterTheTurns) {
  // Turns of 90 deg and more (a zig-zag and a reversal), started facing away from the first leg.
  const std::vector<Eigen::Vector2d> mission{{300, 0}, {300, 300}, {0, 300}, {300, 0}, {600, 0}};
  const model::Pose2 start{0.0, 0.0, kPi};
  const LegRun paper = drive(mission, start, 0.0, 2000.0);
  const LegRun path = drive(mission, start, 3.0, 2000.0);
  print("5 legs, paper", paper);
  print("5 legs, path 3 m", path);
  ASSERT_TRUE(paper.done);
  ASSERT_TRUE(path.done);
  EXPECT_GT(paper.cross_track_rms_m, 5.0);
  EXPECT_LT(path.cross_track_rms_m, 0.5);
  EXPECT_LE(path.time_to_final_s, paper.time_to_final_s);
}

TEST(PathLawParams, NegativeLookaheadIsRefusedByName) {
  ControllerParams params;
  params.path_lookahead_m = -1.0;
  try {
    params.validate();
    FAIL() << "accepted a negative lookahead";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("path_lookahead_m"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace robodds::waypoint_controller
