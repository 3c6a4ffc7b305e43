#pragma once
// Every parameter of the open_loop_commander component: the command profile (OpenLoopParams)
// plus the node's own. config/open_loop_commander.params.yaml is generated from the table.

#include <cstdint>
#include <string>
#include <vector>

#include "common/param_table.hpp"
#include "sim/open_loop_commander/open_loop_commander.hpp"

namespace robodds::open_loop_commander {

// Units, ranges and one-line descriptions of these fields: open_loop_commander_param_table() in
// open_loop_commander_params.cpp (the one source; `robodds components --params open_loop_commander`
// prints it). Defaults: the member initialisers.
struct OpenLoopNodeParams {
  double rate_hz = 50.0;
  OpenLoopParams profile;
  std::int64_t inject_nan_at_step = -1;
};

const params::ParamTable<OpenLoopNodeParams>& open_loop_commander_param_table();

}  // namespace robodds::open_loop_commander
