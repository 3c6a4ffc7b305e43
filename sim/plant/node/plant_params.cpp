#include "sim/plant/node/plant_params.hpp"

#include "sim/plant/node/plant_node.hpp"

namespace robodds::plant {

const params::ParamTable<PlantNodeParams>& plant_param_table() {
  static const params::ParamTable<PlantNodeParams> table =
      params::ParamTable<PlantNodeParams>(
          "Differential-drive plant (paper 1, eq. 1). Integrates exactly over each step the command of\n"
          "the previous step (lockstep) or the newest fresh command (real time).")
          .add("rate_hz", &PlantNodeParams::rate_hz, "Hz", params::positive(),
               "integration/publication rate; must divide the simulation rate")
          .include(&PlantNodeParams::plant, plant_model_param_table());
  return table;
}

}  // namespace robodds::plant
