#include "components/waypoint_controller/control_law.hpp"

#include <cmath>

#include "common/angle.hpp"
#include "common/model/actuator.hpp"
#include "common/model/twist.hpp"

namespace robodds::waypoint_controller {
namespace {
constexpr double kHalfPi = 0.5 * kPi;
}  // namespace

int sgn_star(double alpha_rad) {
  const double magnitude = std::abs(alpha_rad);
  if (magnitude < kHalfPi) {
    return 1;
  }
  if (magnitude > kHalfPi) {
    return -1;
  }
  return 0;
}

bool uses_forward_gains(double alpha_rad) { return std::abs(alpha_rad) <= kHalfPi; }

const GainSet& select_gains(const ControllerParams& params, double alpha_rad) {
  return uses_forward_gains(alpha_rad) ? params.forward_gains : params.backward_gains;
}

Command control_law(const PolarError& error, const GainSet& gains) {
  Command command;
  command.v = gains.kd * error.distance_m;
  command.omega = gains.ka * error.alpha_rad + sgn_star(error.alpha_rad) * gains.ksigma * error.sigma_rad;
  return command;
}

Command brakeable(const Command& command, const GainSet& gains, const model::ActuatorLimits& limits) {
  const auto bound = [](double value, double gain, double max_accel) {
    if (!(max_accel > 0.0) || gain == 0.0) {
      return value;
    }
    // The error the law drives to zero is value / gain; stopping from `value` within it at
    // max_accel needs |value| <= sqrt(2 max_accel |value / gain|).
    const double magnitude = std::abs(value);
    const double reachable = std::sqrt(2.0 * max_accel * magnitude / std::abs(gain));
    return magnitude <= reachable ? value : std::copysign(reachable, value);
  };
  return Command{bound(command.v, gains.kd, limits.max_accel_mps2),
                 bound(command.omega, gains.ka, limits.max_angular_accel_radps2)};
}

Command within_limits(const Command& law_output, const GainSet& gains, const ControllerParams& params) {
  const Command raw = brakeable(law_output, gains, params.body.actuator);
  const model::Twist limited = model::saturate(model::Twist{raw.v, raw.omega},
                                               model::TwistLimits{params.max_speed_mps, params.max_turn_rate_radps});
  const model::Twist within_wheels =
      model::scale_to_wheel_limit(limited, params.body.wheel_base_m, params.body.actuator.max_wheel_speed_mps);
  return Command{within_wheels.v, within_wheels.omega};
}

Command waypoint_command(const PolarError& error, const ControllerParams& params) {
  const GainSet& gains = select_gains(params, error.alpha_rad);
  return within_limits(control_law(error, gains), gains, params);
}

}  // namespace robodds::waypoint_controller
