#include "sim/open_loop_commander/node/open_loop_commander_params.hpp"

#include "sim/open_loop_commander/node/open_loop_commander_node.hpp"

namespace robodds::open_loop_commander {

const params::ParamTable<OpenLoopNodeParams>& open_loop_commander_param_table() {
  static const params::ParamTable<OpenLoopNodeParams> table =
      params::ParamTable<OpenLoopNodeParams>(
          "Open-loop velocity commands for smoke tests: v constant, omega a sine wave whose phase is\n"
          "shifted per robot so robots drive different curves.")
          .add("rate_hz", &OpenLoopNodeParams::rate_hz, "Hz", params::positive(),
               "command rate; must divide the simulation rate")
          .include(&OpenLoopNodeParams::profile, open_loop_param_table())
          .add("inject_nan_at_step", &OpenLoopNodeParams::inject_nan_at_step, "", params::any<long long>(),
               "step at which v is sent as NaN (fault injection for tests); -1 = never");
  return table;
}

}  // namespace robodds::open_loop_commander
