#include "components/waypoint_controller/control_law.hpp"

#include <cmath>

#include "common/angle.hpp"
#include "common/model/actuator.hpp"
#include "common/model/twist.hpp"

namespace robodds::waypoint {
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

Command waypoint_command(const PolarError& error, const ControllerParams& params) {
  const Command raw = control_law(error, select_gains(params, error.alpha_rad));
  const model::Twist limited = model::saturate(model::Twist{raw.v, raw.omega},
                                               model::TwistLimits{params.max_speed_mps, params.max_turn_rate_radps});
  const model::Twist within_wheels =
      model::scale_to_wheel_limit(limited, params.wheel_base_m, params.actuator.max_wheel_speed_mps);
  return Command{within_wheels.v, within_wheels.omega};
}

}  // namespace robodds::waypoint
