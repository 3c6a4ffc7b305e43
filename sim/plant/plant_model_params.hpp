#pragma once
// Parameters of the differential-drive plant model. The robot's physical description (wheel base,
// speed and actuator limits) is not among them: it is the scenario's shared fact robot_body
// (common/model/robot_body.hpp, system/robot_facts.hpp), which the plant simulates per robot.
#include "common/param_table.hpp"
#include "sim/plant/disturbance.hpp"

namespace robodds::plant {

// Units, ranges and one-line descriptions of these fields: plant_model_param_table() in
// plant_params.cpp (the one source; `robodds components --params plant` prints it). Defaults: the
// member initialisers.
struct PlantParams {
  double command_timeout_s = 0.5;
  PoseDisturbance disturbance;  // flat keys disturbance_at_s, disturbance_dx_m, ... (not nested)

  /// Throws std::invalid_argument("key: reason").
  void validate() const;
};

const params::ParamTable<PlantParams>& plant_model_param_table();

}  // namespace robodds::plant
