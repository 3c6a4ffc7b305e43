#include "sim/open_loop/open_loop_commander.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "common/angle.hpp"

namespace robodds::open_loop {

void OpenLoopParams::validate() const {
  if (!(omega_period_s > 0.0)) {
    throw std::invalid_argument("omega_period_s: must be > 0 (got " + std::to_string(omega_period_s) + ")");
  }
}

TwistCommand open_loop_command(const OpenLoopParams& params, std::size_t robot_index, double time_s) {
  const double phase = 2.0 * kPi * time_s / params.omega_period_s + params.phase_per_robot_rad * static_cast<double>(robot_index);
  return TwistCommand{params.v_mps, params.omega_bias_radps + params.omega_amplitude_radps * std::sin(phase)};
}

}  // namespace robodds::open_loop
