#pragma once
// Open-loop command profile for smoke scenarios. Pure: time in s, SI units.
#include <cstddef>

#include "common/param_table.hpp"

namespace robodds::open_loop_commander {

// Units, ranges and one-line descriptions of these fields: open_loop_param_table() in
// open_loop_commander.cpp (the one source; `robodds components --params open_loop_commander`
// prints it). Defaults: the member initialisers.
struct OpenLoopParams {
  double v_mps = 1.0;
  double omega_bias_radps = 0.05;
  double omega_amplitude_radps = 0.3;
  double omega_period_s = 8.0;
  double phase_per_robot_rad = 1.0;
  void validate() const;  // throws std::invalid_argument("key: reason")
};

/// Keys, units, ranges and descriptions of OpenLoopParams (defaults: the initialisers above).
const params::ParamTable<OpenLoopParams>& open_loop_param_table();

struct TwistCommand {
  double v = 0.0;      // m/s
  double omega = 0.0;  // rad/s
};

/// Command of the robot with index `robot_index` (0-based, in scenario order) at time t.
TwistCommand open_loop_command(const OpenLoopParams& params, std::size_t robot_index, double time_s);

}  // namespace robodds::open_loop_commander
