#include "components/waypoint_controller/controller_params.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

#include "tests/support/validation_error.hpp"

namespace robodds::waypoint_controller {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using test_support::validation_error;

bool starts_with(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

ControllerParams with_forward(GainSet gains) {
  ControllerParams params;
  params.forward_gains = gains;
  return params;
}

ControllerParams with_backward(GainSet gains) {
  ControllerParams params;
  params.backward_gains = gains;
  return params;
}

TEST(WaypointControllerParams, DefaultsAreThePapersGainsAndPass) {
  const ControllerParams params;
  EXPECT_NO_THROW(params.validate());
  EXPECT_EQ(params.forward_gains.kd, 1.0);
  EXPECT_EQ(params.forward_gains.ka, 20.0);
  EXPECT_EQ(params.forward_gains.ksigma, -2.5);
  EXPECT_EQ(params.backward_gains.kd, -1.0);
  EXPECT_EQ(params.backward_gains.ka, 20.0);
  EXPECT_EQ(params.backward_gains.ksigma, -2.5);
  EXPECT_EQ(params.epsilon_m, 0.1);
  EXPECT_EQ(params.max_speed_mps, 0.0);
  EXPECT_EQ(params.max_turn_rate_radps, 0.0);
  EXPECT_TRUE(params.stop_when_done);  // not the paper's: the scenarios' (YAML) value since issue 8
}

TEST(WaypointControllerParams, PapersTableOneThresholdsAndLimitsPass) {
  for (const double epsilon : {0.1, 0.01, 0.001}) {
    ControllerParams params;
    params.epsilon_m = epsilon;
    params.max_speed_mps = 1.0;
    params.max_turn_rate_radps = 1.0;
    EXPECT_EQ(validation_error(params), "") << epsilon;
  }
}

TEST(WaypointControllerParams, ForwardKdMustBePositive) {
  const std::string message = validation_error(with_forward({0.0, 20.0, -2.5}));
  EXPECT_TRUE(starts_with(message, "forward_gains: violates eq. (11) kd > 0")) << message;
  EXPECT_TRUE(contains(message, "kd=0, ka=20, ksigma=-2.5")) << message;
}

TEST(WaypointControllerParams, ForwardKsigmaMustBeNegative) {
  const std::string message = validation_error(with_forward({1.0, 20.0, 2.5}));
  EXPECT_TRUE(starts_with(message, "forward_gains: violates eq. (11) sgn*·ksigma < 0")) << message;
}

TEST(WaypointControllerParams, ForwardGainSumMustBePositive) {
  // -2.5 + 3 - 1 = -0.5.
  const std::string message = validation_error(with_forward({1.0, 3.0, -2.5}));
  EXPECT_TRUE(starts_with(message, "forward_gains: violates eq. (11) sgn*·ksigma + ka - kd > 0")) << message;
}

TEST(WaypointControllerParams, ForwardAuxiliaryConditionIsChecked) {
  // Eq. (11) holds (-10 + 20 - 1 = 9) but eq. (16) does not (-20 + 20 - 2/pi < 0).
  const std::string message = validation_error(with_forward({1.0, 20.0, -10.0}));
  EXPECT_TRUE(starts_with(message, "forward_gains: violates eq. (16) 2·sgn*·ksigma + ka - (2/pi)·kd > 0")) << message;
}

TEST(WaypointControllerParams, BackwardKdMustBeNegative) {
  const std::string message = validation_error(with_backward({1.0, 20.0, -2.5}));
  EXPECT_TRUE(starts_with(message, "backward_gains: violates eq. (11) read for the backward set: kd < 0")) << message;
}

TEST(WaypointControllerParams, BackwardSignProductMustBeNegative) {
  const std::string message = validation_error(with_backward({-1.0, 20.0, 2.5}));
  EXPECT_TRUE(starts_with(message, "backward_gains: violates eq. (11) read for the backward set: sgn*·ksigma·kd < 0"))
      << message;
}

TEST(WaypointControllerParams, BackwardPrintedGainSumIsChecked) {
  // 2.5 - 5 + 1 = -1.5.
  const std::string message = validation_error(with_backward({-1.0, -5.0, -2.5}));
  EXPECT_TRUE(starts_with(message, "backward_gains: violates eq. (11) sgn*·ksigma + ka - kd > 0")) << message;
}

TEST(WaypointControllerParams, BackwardLyapunovBracketAtSmallSincIsChecked) {
  // Printed sum holds (2.5 - 3 + 1 = 0.5) but 2.5 - 3 < 0.
  const std::string message = validation_error(with_backward({-1.0, -3.0, -2.5}));
  EXPECT_TRUE(starts_with(message, "backward_gains: violates eq. (11) read for the backward set: sgn*·ksigma + ka > 0"))
      << message;
}

TEST(WaypointControllerParams, BackwardAuxiliaryConditionIsChecked) {
  // Eq. (11) holds; 20 - 24 + 2/pi < 0: alpha could run away from pi/2 towards pi.
  const std::string message = validation_error(with_backward({-1.0, 20.0, -12.0}));
  EXPECT_TRUE(starts_with(message, "backward_gains: violates eq. (16) read for the backward set")) << message;
}

TEST(WaypointControllerParams, BackwardConditionAtPiIsChecked) {
  // Boundary condition holds thanks to the large |kd| (9 - 20 + 63.7 > 0), but at alpha = pi
  // ka = 9 cannot beat |ksigma|·pi = 10·pi.
  const std::string message = validation_error(with_backward({-100.0, 9.0, -10.0}));
  EXPECT_TRUE(starts_with(message, "backward_gains: violates eq. (18) at alpha = pi: ka - |ksigma| > 0")) << message;
}

TEST(WaypointControllerParams, NonFiniteGainsNameTheField) {
  EXPECT_EQ(validation_error(with_forward({kNan, 20.0, -2.5})), "forward_gains.kd: must be finite (got nan)");
  EXPECT_EQ(validation_error(with_forward({1.0, kInf, -2.5})), "forward_gains.ka: must be finite (got inf)");
  EXPECT_EQ(validation_error(with_backward({-1.0, 20.0, -kInf})), "backward_gains.ksigma: must be finite (got -inf)");
}

TEST(WaypointControllerParams, EpsilonMustBePositiveAndFinite) {
  for (const double bad : {0.0, -0.1, kNan, kInf}) {
    ControllerParams params;
    params.epsilon_m = bad;
    EXPECT_TRUE(starts_with(validation_error(params), "epsilon_m: must be > 0 and finite")) << bad;
  }
}

TEST(WaypointControllerParams, LimitsMustBeNonNegativeAndFinite) {
  for (const double bad : {-1.0, kNan, kInf}) {
    ControllerParams speed;
    speed.max_speed_mps = bad;
    EXPECT_TRUE(starts_with(validation_error(speed), "max_speed_mps: must be >= 0")) << bad;
    ControllerParams turn;
    turn.max_turn_rate_radps = bad;
    EXPECT_TRUE(starts_with(validation_error(turn), "max_turn_rate_radps: must be >= 0")) << bad;
    ControllerParams wheel;
    wheel.body.actuator.max_wheel_speed_mps = bad;
    EXPECT_TRUE(starts_with(validation_error(wheel), "max_wheel_speed_mps: must be >= 0")) << bad;
    ControllerParams accel;
    accel.body.actuator.max_accel_mps2 = bad;
    EXPECT_TRUE(starts_with(validation_error(accel), "max_accel_mps2: must be >= 0")) << bad;
    ControllerParams angular;
    angular.body.actuator.max_angular_accel_radps2 = bad;
    EXPECT_TRUE(starts_with(validation_error(angular), "max_angular_accel_radps2: must be >= 0")) << bad;
  }
  for (const double bad : {0.0, -0.3, kNan}) {
    ControllerParams track;
    track.body.wheel_base_m = bad;
    EXPECT_TRUE(starts_with(validation_error(track), "wheel_base_m: must be > 0")) << bad;
  }
}

}  // namespace
}  // namespace robodds::waypoint_controller
