#pragma once
// Every parameter of the plant component: the plant's (PlantParams) plus the node's rate. The table is the one source of the keys,
// defaults (the member initialisers), units, ranges and descriptions;
// config/plant.params.yaml is generated from it.

#include <cstdint>
#include <string>
#include <vector>

#include "common/param_table.hpp"
#include "sim/plant/plant_params.hpp"

namespace robodds::plant {

struct PlantNodeParams {
  double rate_hz = 100.0;
  PlantParams plant;
};

const params::ParamTable<PlantNodeParams>& plant_param_table();

}  // namespace robodds::plant
