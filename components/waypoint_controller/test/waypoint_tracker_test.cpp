#include "components/waypoint_controller/waypoint_tracker.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/angle.hpp"

namespace robodds::waypoint_controller {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kTol = 1e-12;

/// Three way-points on the x axis, 10 m apart.
std::vector<Eigen::Vector2d> line_mission() {
  return {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(10.0, 0.0), Eigen::Vector2d(20.0, 0.0)};
}

// The paper's behaviour at the last way-point: the law stays active there (stop_when_done,
// whose default is true since the parameter table became the one source of defaults).
ControllerParams paper_params() {
  ControllerParams params;
  params.stop_when_done = false;
  return params;
}

WaypointTracker line_tracker() {
  WaypointTracker tracker(paper_params());  // epsilon 0.1 m
  tracker.set_mission(line_mission());
  return tracker;
}

std::string invalid_argument_message(WaypointTracker& tracker, std::vector<Eigen::Vector2d> mission) {
  try {
    tracker.set_mission(std::move(mission));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(WaypointTracker, ConstructorValidatesParams) {
  ControllerParams params;
  params.epsilon_m = 0.0;
  EXPECT_THROW(WaypointTracker{params}, std::invalid_argument);
}

TEST(WaypointTracker, StartsWithoutMission) {
  WaypointTracker tracker;
  EXPECT_FALSE(tracker.has_mission());
  EXPECT_THROW(tracker.step(0.0, 0.0, 0.0), std::logic_error);
}

TEST(WaypointTracker, EmptyMissionIsRejectedAndKeepsTheOldOne) {
  WaypointTracker tracker = line_tracker();
  EXPECT_EQ(invalid_argument_message(tracker, {}),
            "set_mission: the mission is empty (needs at least one way-point)");
  EXPECT_EQ(tracker.mission().size(), 3u);
}

TEST(WaypointTracker, NonFiniteWaypointIsRejectedWithItsIndex) {
  WaypointTracker tracker;
  const std::string message =
      invalid_argument_message(tracker, {Eigen::Vector2d(1.0, 2.0), Eigen::Vector2d(kNan, 2.0)});
  EXPECT_EQ(message, "set_mission: way-point 1 is not finite (got (nan, 2))");
  EXPECT_FALSE(tracker.has_mission());
  const std::string infinite = invalid_argument_message(
      tracker, {Eigen::Vector2d(1.0, std::numeric_limits<double>::infinity())});
  EXPECT_EQ(infinite, "set_mission: way-point 0 is not finite (got (1, inf))");
}

TEST(WaypointTracker, NonFinitePoseThrowsAndLeavesStateUnchanged) {
  WaypointTracker tracker = line_tracker();
  tracker.step(0.05, 0.0, 0.0);  // reaches way-point 0
  ASSERT_EQ(tracker.target_index(), 1u);
  EXPECT_THROW(tracker.step(kNan, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(tracker.step(10.0, kNan, 0.0), std::invalid_argument);
  EXPECT_THROW(tracker.step(10.0, 0.0, std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_EQ(tracker.target_index(), 1u);
  EXPECT_EQ(tracker.reached_count(), 1u);
  EXPECT_FALSE(tracker.done());
}

TEST(WaypointTracker, NoSwitchJustOutsideEpsilon) {
  WaypointTracker tracker = line_tracker();
  const TrackerOutput output = tracker.step(std::nextafter(0.1, 1.0), 0.0, 0.0);
  EXPECT_EQ(output.status.target_index, 0u);
  EXPECT_EQ(output.status.reached_count, 0u);
  EXPECT_FALSE(output.status.reached_this_step);
  EXPECT_TRUE(std::isnan(output.status.reached_distance_m));
}

TEST(WaypointTracker, SwitchesAtExactlyEpsilonAndAimsAtTheNextOneAtOnce) {
  WaypointTracker tracker = line_tracker();
  const TrackerOutput output = tracker.step(0.1, 0.0, 0.0);  // ||p - W_0|| = 0.1 = epsilon
  EXPECT_TRUE(output.status.reached_this_step);
  EXPECT_EQ(output.status.reached_distance_m, 0.1);
  EXPECT_EQ(output.status.target_index, 1u);
  EXPECT_EQ(output.status.reached_count, 1u);
  EXPECT_NEAR(output.status.distance_to_target_m, 9.9, kTol);
  EXPECT_NEAR(output.status.distance_to_final_m, 19.9, kTol);
  EXPECT_NEAR(output.status.alpha_rad, 0.0, kTol);          // W_1 straight ahead
  EXPECT_NEAR(output.command.v, 9.9, kTol);                 // kd·d to W_1
  EXPECT_NEAR(output.command.omega, -2.5 * kPi / 2, kTol);  // sigma = pi/2
  EXPECT_EQ(tracker.reach_distances_m(), std::vector<double>{0.1});
}

TEST(WaypointTracker, OneSwitchPerStepForCoincidentWaypoints) {
  WaypointTracker tracker;
  tracker.set_mission({Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(5.0, 5.0)});
  EXPECT_EQ(tracker.step(0.0, 0.0, 0.0).status.target_index, 1u);
  EXPECT_EQ(tracker.step(0.0, 0.0, 0.0).status.target_index, 2u);
  EXPECT_EQ(tracker.reached_count(), 2u);
}

TEST(WaypointTracker, StaysOnTheLastWaypointAndLatchesDone) {
  WaypointTracker tracker = line_tracker();
  tracker.step(0.0, 0.0, 0.0);
  tracker.step(10.0, 0.0, 0.0);
  EXPECT_FALSE(tracker.step(19.0, 0.0, 0.0).status.done);

  const TrackerOutput arrival = tracker.step(20.05, 0.0, 0.0);
  EXPECT_TRUE(arrival.status.done);
  EXPECT_TRUE(arrival.status.reached_this_step);
  EXPECT_EQ(arrival.status.target_index, 2u);
  EXPECT_EQ(arrival.status.reached_count, 3u);
  EXPECT_NEAR(arrival.status.reached_distance_m, 0.05, kTol);
  // The law stays active on the last way-point: it is behind, so the robot backs up to it.
  EXPECT_NEAR(arrival.command.v, -0.05, kTol);

  // Pushed away again: still done, still the last index, no extra "reached", law still active.
  const TrackerOutput later = tracker.step(21.0, 0.0, kPi);
  EXPECT_TRUE(later.status.done);
  EXPECT_FALSE(later.status.reached_this_step);
  EXPECT_EQ(later.status.target_index, 2u);
  EXPECT_EQ(later.status.reached_count, 3u);
  EXPECT_NEAR(later.command.v, 1.0, kTol);  // facing it: forward at kd·d
  EXPECT_EQ(tracker.reach_distances_m().size(), 3u);
}

TEST(WaypointTracker, StandingExactlyOnTheLastWaypointIsFinite) {
  WaypointTracker tracker;
  tracker.set_mission({Eigen::Vector2d(4.0, 2.0)});
  for (int i = 0; i < 3; ++i) {
    const TrackerOutput output = tracker.step(4.0, 2.0, 0.3);
    EXPECT_EQ(output.command.v, 0.0);
    EXPECT_TRUE(std::isfinite(output.command.omega));
    EXPECT_EQ(output.status.alpha_rad, 0.0);
    EXPECT_EQ(output.status.distance_to_final_m, 0.0);
    EXPECT_TRUE(output.status.done);
  }
  EXPECT_EQ(tracker.reached_count(), 1u);
}

TEST(WaypointTracker, NewMissionRestarts) {
  WaypointTracker tracker = line_tracker();
  tracker.step(0.0, 0.0, 0.0);
  tracker.set_mission({Eigen::Vector2d(1.0, 1.0)});
  EXPECT_EQ(tracker.target_index(), 0u);
  EXPECT_EQ(tracker.reached_count(), 0u);
  EXPECT_FALSE(tracker.done());
  EXPECT_TRUE(tracker.reach_distances_m().empty());
}

TEST(WaypointTracker, AppliesTheConfiguredLimits) {
  ControllerParams params;
  params.max_speed_mps = 1.0;
  params.max_turn_rate_radps = 1.0;
  WaypointTracker tracker(params);
  tracker.set_mission(line_mission());
  const TrackerOutput output = tracker.step(-18.0, 3.0, 2.0);
  EXPECT_LE(std::abs(output.command.v), 1.0);
  EXPECT_LE(std::abs(output.command.omega), 1.0);
}

// Issue 12: with acceleration limits each command differs from the previous one by at most
// max_accel * period (v) and max_angular_accel * period (omega), the stop included.
TEST(WaypointTracker, RampsItsCommandsAtTheAccelerationLimits) {
  ControllerParams params = paper_params();
  params.body.actuator.max_accel_mps2 = 1.0;
  params.body.actuator.max_angular_accel_radps2 = 5.0;
  params.stop_when_done = true;
  WaypointTracker tracker(params, 0.1);
  tracker.set_mission({Eigen::Vector2d(10.0, 0.0)});
  Command previous{};
  for (int k = 0; k < 5; ++k) {
    const TrackerOutput out = tracker.step(0.0, 0.0, 0.0);
    EXPECT_NEAR(out.command.v, 0.1 * (k + 1), kTol) << "step " << k << ": +1 m/s^2 * 0.1 s per step";
    EXPECT_LE(std::abs(out.command.omega - previous.omega), 0.5 + kTol);
    previous = out.command;
  }
  // On the way-point: done, the stop ramps down too.
  const TrackerOutput stop = tracker.step(10.0, 0.0, kPi / 2);
  ASSERT_TRUE(stop.status.done);
  EXPECT_NEAR(stop.command.v, 0.4, kTol);
  // The node sent a stop of its own (no valid estimate): the ramp restarts from zero.
  tracker.command_stopped();
  EXPECT_NEAR(tracker.step(10.0, 0.0, kPi / 2).command.v, 0.0, kTol);
}

TEST(WaypointTracker, AccelerationLimitsNeedAControlPeriod) {
  ControllerParams params;
  params.body.actuator.max_accel_mps2 = 1.0;
  try {
    WaypointTracker tracker(params);
    FAIL() << "no period accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("period_s: must be > 0", 0), 0u) << e.what();
  }
  EXPECT_NO_THROW(WaypointTracker(params, 0.01));
  EXPECT_NO_THROW(WaypointTracker(ControllerParams{})) << "without acceleration limits no period is needed";
}

WaypointTracker confident_tracker(double kappa) {
  ControllerParams params;
  params.confidence_switch_sigmas = kappa;
  WaypointTracker tracker(params);
  tracker.set_mission(line_mission());
  return tracker;
}

TEST(WaypointTrackerConfidence, OffByDefaultSoOnlyEpsilonSwitches) {
  WaypointTracker tracker = line_tracker();
  const Eigen::Matrix2d wide = Eigen::Matrix2d::Identity() * 100.0;  // 10 m sigma
  const TrackerOutput out = tracker.step(0.5, 0.0, 0.0, wide);
  EXPECT_FALSE(out.status.reached_this_step);
  EXPECT_EQ(tracker.target_index(), 0u);
}

TEST(WaypointTrackerConfidence, SwitchesWhenTheWaypointIsInsideTheKappaSigmaEllipse) {
  WaypointTracker tracker = confident_tracker(1.0);
  Eigen::Matrix2d covariance;
  covariance << 0.09, 0.0, 0.0, 0.04;  // sigma 0.3 m along x, 0.2 m along y
  // 0.25 m along x: Mahalanobis 0.83 <= 1 -> reached although 0.25 > epsilon.
  const TrackerOutput out = tracker.step(0.25, 0.0, 0.0, covariance);
  EXPECT_TRUE(out.status.reached_this_step);
  EXPECT_NEAR(out.status.reached_distance_m, 0.25, kTol);
  EXPECT_EQ(tracker.target_index(), 1u);
}

TEST(WaypointTrackerConfidence, UsesTheEllipseNotTheMeanSigma) {
  WaypointTracker tracker = confident_tracker(1.0);
  Eigen::Matrix2d covariance;
  covariance << 0.09, 0.0, 0.0, 0.04;
  // 0.25 m along y: Mahalanobis 1.25 > 1 -> not reached (it would be with sigma 0.3 m).
  EXPECT_FALSE(tracker.step(0.0, 0.25, 0.0, covariance).status.reached_this_step);
  EXPECT_EQ(tracker.target_index(), 0u);
}

TEST(WaypointTrackerConfidence, ZeroOrBrokenCovarianceFallsBackToEpsilon) {
  WaypointTracker tracker = confident_tracker(3.0);
  EXPECT_FALSE(tracker.step(0.5, 0.0, 0.0, Eigen::Matrix2d::Zero()).status.reached_this_step);
  Eigen::Matrix2d broken;
  broken << kNan, 0.0, 0.0, 1.0;
  EXPECT_FALSE(tracker.step(0.5, 0.0, 0.0, broken).status.reached_this_step);
  Eigen::Matrix2d indefinite;
  indefinite << 1.0, 0.0, 0.0, -1.0;
  EXPECT_FALSE(tracker.step(0.5, 0.0, 0.0, indefinite).status.reached_this_step);
  EXPECT_TRUE(tracker.step(0.05, 0.0, 0.0, Eigen::Matrix2d::Zero()).status.reached_this_step);
}

TEST(WaypointTrackerConfidence, NegativeOrNonFiniteKappaIsRejectedByName) {
  ControllerParams params;
  params.confidence_switch_sigmas = -1.0;
  EXPECT_THROW(
      {
        try {
          params.validate();
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("confidence_switch_sigmas"), std::string::npos) << e.what();
          throw;
        }
      },
      std::invalid_argument);
  params.confidence_switch_sigmas = kNan;
  EXPECT_THROW(params.validate(), std::invalid_argument);
}

TEST(WaypointTracker, StopWhenDoneCommandsZeroAfterTheLastWaypoint) {
  ControllerParams params;
  params.stop_when_done = true;
  WaypointTracker tracker(params);
  tracker.set_mission({Eigen::Vector2d(0.0, 0.0)});
  const TrackerOutput before = tracker.step(5.0, 0.0, 0.0);
  EXPECT_NE(before.command.v, 0.0);  // still driving
  const TrackerOutput reached = tracker.step(0.05, 0.0, 1.0);
  EXPECT_TRUE(reached.status.done);
  EXPECT_EQ(reached.command.v, 0.0);
  EXPECT_EQ(reached.command.omega, 0.0);
  const TrackerOutput after = tracker.step(0.5, 0.3, -2.0);  // drifted: stays stopped
  EXPECT_EQ(after.command.v, 0.0);
  EXPECT_EQ(after.command.omega, 0.0);
}

TEST(WaypointTracker, WithoutStopWhenDoneTheLawStaysActiveAtTheLastWaypoint) {
  WaypointTracker tracker(paper_params());
  tracker.set_mission({Eigen::Vector2d(0.0, 0.0)});
  EXPECT_TRUE(tracker.step(0.05, 0.0, 1.0).status.done);
  EXPECT_NE(tracker.step(0.5, 0.3, -2.0).command.omega, 0.0);
}

}  // namespace
}  // namespace robodds::waypoint_controller
