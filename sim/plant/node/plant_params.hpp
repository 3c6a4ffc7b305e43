#pragma once
// Every parameter of the plant component: the plant's (PlantParams) plus the node's rate.
// config/plant.params.yaml is generated from the table.

#include <cstdint>
#include <string>
#include <vector>

#include "common/param_table.hpp"
#include "sim/plant/plant_model_params.hpp"

namespace robodds::plant {

// Units, ranges and one-line descriptions of these fields: plant_param_table() in
// plant_node_params.cpp (the one source; `robodds components --params plant` prints it). Defaults:
// the member initialisers.
struct PlantNodeParams {
  double rate_hz = 100.0;
  PlantParams plant;
};

const params::ParamTable<PlantNodeParams>& plant_param_table();

}  // namespace robodds::plant
