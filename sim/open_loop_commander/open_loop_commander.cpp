#include "sim/open_loop_commander/open_loop_commander.hpp"

#include <cmath>

#include "common/angle.hpp"

namespace robodds::open_loop_commander {

const params::ParamTable<OpenLoopParams>& open_loop_param_table() {
  static const params::ParamTable<OpenLoopParams> table =
      params::ParamTable<OpenLoopParams>()
          .add("v_mps", &OpenLoopParams::v_mps, "m/s", params::finite(), "forward speed")
          .add("omega_bias_radps", &OpenLoopParams::omega_bias_radps, "rad/s", params::finite(),
               "constant part of the turn rate")
          .add("omega_amplitude_radps", &OpenLoopParams::omega_amplitude_radps, "rad/s", params::finite(),
               "amplitude of the sine part")
          .add("omega_period_s", &OpenLoopParams::omega_period_s, "s", params::positive(), "period of the sine part")
          .add("phase_per_robot_rad", &OpenLoopParams::phase_per_robot_rad, "rad", params::finite(),
               "phase shift between consecutive robots");
  return table;
}

void OpenLoopParams::validate() const { open_loop_param_table().check_ranges(*this); }

TwistCommand open_loop_command(const OpenLoopParams& params, std::size_t robot_index, double time_s) {
  const double phase = 2.0 * kPi * time_s / params.omega_period_s + params.phase_per_robot_rad * static_cast<double>(robot_index);
  return TwistCommand{params.v_mps, params.omega_bias_radps + params.omega_amplitude_radps * std::sin(phase)};
}

}  // namespace robodds::open_loop_commander
