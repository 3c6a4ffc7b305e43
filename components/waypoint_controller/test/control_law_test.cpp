#include "components/waypoint_controller/control_law.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>

#include "common/angle.hpp"

namespace robodds::waypoint_controller {
namespace {

constexpr double kTol = 1e-12;
constexpr double kHalfPi = kPi / 2;

PolarError error_of(double distance_m, double alpha_rad, double sigma_rad) {
  PolarError error;
  error.distance_m = distance_m;
  error.alpha_rad = alpha_rad;
  error.sigma_rad = sigma_rad;
  return error;
}

TEST(WaypointSgnStar, IsOneInsideHalfPi) {
  EXPECT_EQ(sgn_star(0.0), 1);
  EXPECT_EQ(sgn_star(1.0), 1);
  EXPECT_EQ(sgn_star(-1.0), 1);
  EXPECT_EQ(sgn_star(std::nextafter(kHalfPi, 0.0)), 1);
  EXPECT_EQ(sgn_star(-std::nextafter(kHalfPi, 0.0)), 1);
}

TEST(WaypointSgnStar, IsZeroAtExactlyHalfPi) {
  EXPECT_EQ(sgn_star(kHalfPi), 0);
  EXPECT_EQ(sgn_star(-kHalfPi), 0);
}

TEST(WaypointSgnStar, IsMinusOneBeyondHalfPi) {
  EXPECT_EQ(sgn_star(std::nextafter(kHalfPi, 4.0)), -1);
  EXPECT_EQ(sgn_star(-std::nextafter(kHalfPi, 4.0)), -1);
  EXPECT_EQ(sgn_star(kPi), -1);
  EXPECT_EQ(sgn_star(-3.0), -1);
}

TEST(WaypointGainChoice, ForwardUpToAndIncludingHalfPiBackwardBeyond) {
  const ControllerParams params;
  EXPECT_TRUE(uses_forward_gains(0.0));
  EXPECT_TRUE(uses_forward_gains(kHalfPi));
  EXPECT_TRUE(uses_forward_gains(-kHalfPi));
  EXPECT_FALSE(uses_forward_gains(std::nextafter(kHalfPi, 4.0)));
  EXPECT_FALSE(uses_forward_gains(kPi));
  EXPECT_EQ(&select_gains(params, 0.3), &params.forward_gains);
  EXPECT_EQ(&select_gains(params, kHalfPi), &params.forward_gains);
  EXPECT_EQ(&select_gains(params, -2.0), &params.backward_gains);
}

TEST(WaypointControlLaw, ForwardHandComputed) {
  // v = 1·2 = 2; omega = 20·0.1 + (+1)·(-2.5)·0.5 = 0.75.
  const Command command = control_law(error_of(2.0, 0.1, 0.5), ControllerParams{}.forward_gains);
  EXPECT_NEAR(command.v, 2.0, kTol);
  EXPECT_NEAR(command.omega, 0.75, kTol);
}

TEST(WaypointControlLaw, BackwardHandComputedBacksUp) {
  // v = -1·3 = -3; omega = 20·2 + (-1)·(-2.5)·(-1) = 37.5.
  const Command command = control_law(error_of(3.0, 2.0, -1.0), ControllerParams{}.backward_gains);
  EXPECT_NEAR(command.v, -3.0, kTol);
  EXPECT_NEAR(command.omega, 37.5, kTol);
}

TEST(WaypointControlLaw, SigmaTermVanishesAtExactlyHalfPi) {
  // sgn* = 0: omega = 20·(pi/2) whatever sigma; forward set, so v = +d.
  const ControllerParams params;
  const Command left = waypoint_command(error_of(1.5, kHalfPi, 0.7), params);
  EXPECT_NEAR(left.v, 1.5, kTol);
  EXPECT_NEAR(left.omega, 10.0 * kPi, kTol);
  const Command right = waypoint_command(error_of(1.5, -kHalfPi, 0.7), params);
  EXPECT_NEAR(right.omega, -10.0 * kPi, kTol);
}

TEST(WaypointControlLaw, CommandPicksTheGainSetByBearing) {
  const ControllerParams params;
  const Command ahead = waypoint_command(error_of(2.0, 0.1, 0.5), params);
  EXPECT_NEAR(ahead.v, 2.0, kTol);
  EXPECT_NEAR(ahead.omega, 0.75, kTol);
  const Command behind = waypoint_command(error_of(3.0, 2.0, -1.0), params);
  EXPECT_NEAR(behind.v, -3.0, kTol);
  EXPECT_NEAR(behind.omega, 37.5, kTol);
}

TEST(WaypointControlLaw, ZeroDistanceGivesZeroSpeedAndFiniteTurn) {
  // On the way-point: alpha = 0 (see polar_error), only the sigma term turns the robot.
  const Command command = waypoint_command(error_of(0.0, 0.0, 0.4), ControllerParams{});
  EXPECT_EQ(command.v, 0.0);
  EXPECT_NEAR(command.omega, -2.5 * 0.4, kTol);
}

TEST(WaypointControlLaw, LimitsClampSpeedAndTurnRateIndependently) {
  ControllerParams params;
  params.max_speed_mps = 1.0;
  params.max_turn_rate_radps = 0.5;
  const Command ahead = waypoint_command(error_of(2.0, 0.1, 0.5), params);
  EXPECT_EQ(ahead.v, 1.0);
  EXPECT_EQ(ahead.omega, 0.5);
  const Command behind = waypoint_command(error_of(3.0, -2.0, 1.0), params);
  EXPECT_EQ(behind.v, -1.0);
  EXPECT_EQ(behind.omega, -0.5);
  const Command small = waypoint_command(error_of(0.2, 0.01, 0.0), params);
  EXPECT_NEAR(small.v, 0.2, kTol);
  EXPECT_NEAR(small.omega, 0.2, kTol);
}

// Issue 12: the faster wheel at its limit, v and omega scaled by one factor (same curvature).
TEST(WaypointControlLaw, WheelLimitScalesSpeedAndTurnRateTogether) {
  ControllerParams params;
  params.body.wheel_base_m = 0.3;
  params.body.actuator.max_wheel_speed_mps = 1.5;
  const PolarError error = error_of(18.0, 1.5, 1.0);
  const Command raw = control_law(error, params.forward_gains);
  const Command command = waypoint_command(error, params);
  const double fastest = std::max(std::abs(command.v - 0.15 * command.omega), std::abs(command.v + 0.15 * command.omega));
  EXPECT_NEAR(fastest, 1.5, kTol);
  EXPECT_NEAR(command.omega / command.v, raw.omega / raw.v, kTol) << "the curvature of eq. (10) is kept";
  const Command slow = waypoint_command(error_of(0.5, 0.01, 0.0), params);
  EXPECT_NEAR(slow.v, 0.5, kTol) << "within the wheel limit: unchanged";
  EXPECT_NEAR(slow.omega, 0.2, kTol);
}

// Issue 12: |v| <= sqrt(2 a d) and |omega| <= sqrt(2 a_omega |omega / ka|): the robot can brake
// before the error the law drives to zero is gone; the sign and the zeros of the law are kept.
TEST(WaypointControlLaw, BrakeableBoundsTheLawWhereTheRobotCouldNotStopInTime) {
  const GainSet gains{1.0, 20.0, -2.5};
  const model::ActuatorLimits limits{0.0, 1.0, 5.0};
  const Command far = brakeable(Command{18.0, -60.0}, gains, limits);
  EXPECT_NEAR(far.v, 6.0, kTol) << "sqrt(2 * 1 * 18)";
  EXPECT_NEAR(far.omega, -std::sqrt(2.0 * 5.0 * 3.0), kTol) << "heading error 60 / 20 = 3 rad";
  const Command near = brakeable(Command{1.5, 0.5}, gains, limits);
  EXPECT_EQ(near.v, 1.5) << "1.5 <= sqrt(3): brakeable";
  EXPECT_EQ(near.omega, 0.5) << "0.5 <= sqrt(0.25)=0.5";
  const Command zero = brakeable(Command{0.0, 0.0}, gains, limits);
  EXPECT_EQ(zero.v, 0.0);
  EXPECT_EQ(zero.omega, 0.0);
  const Command backwards = brakeable(Command{-8.0, 40.0}, GainSet{-1.0, 20.0, -2.5}, limits);
  EXPECT_NEAR(backwards.v, -4.0, kTol) << "backing up: sqrt(2 * 8), sign kept";
  const Command unlimited = brakeable(Command{18.0, -60.0}, gains, model::ActuatorLimits{});
  EXPECT_EQ(unlimited.v, 18.0);
  EXPECT_EQ(unlimited.omega, -60.0);
}

TEST(WaypointControlLaw, ZeroLimitsMeanUnlimited) {
  const Command command = waypoint_command(error_of(18.0, 1.5, 1.0), ControllerParams{});
  EXPECT_NEAR(command.v, 18.0, kTol);
  EXPECT_NEAR(command.omega, 20.0 * 1.5 - 2.5, kTol);
}

}  // namespace
}  // namespace robodds::waypoint_controller
