#include "sim/open_loop/open_loop_commander.hpp"

#include <cmath>

#include "common/angle.hpp"
#include "common/param_checks.hpp"

namespace robodds::open_loop {

void OpenLoopParams::validate() const {
  param_checks::require_finite("v_mps", v_mps);
  param_checks::require_finite("omega_bias_radps", omega_bias_radps);
  param_checks::require_finite("omega_amplitude_radps", omega_amplitude_radps);
  param_checks::require_positive("omega_period_s", omega_period_s);
  param_checks::require_finite("phase_per_robot_rad", phase_per_robot_rad);
}

TwistCommand open_loop_command(const OpenLoopParams& params, std::size_t robot_index, double time_s) {
  const double phase = 2.0 * kPi * time_s / params.omega_period_s + params.phase_per_robot_rad * static_cast<double>(robot_index);
  return TwistCommand{params.v_mps, params.omega_bias_radps + params.omega_amplitude_radps * std::sin(phase)};
}

}  // namespace robodds::open_loop
