#pragma once
// Parameters of the differential-drive plant model.
#include "common/model/actuator.hpp"
#include "common/model/twist.hpp"
#include "common/param_table.hpp"
#include "sim/plant/disturbance.hpp"

namespace robodds::plant {

// Units, ranges and one-line descriptions of these fields: plant_model_param_table() in
// plant_params.cpp (the one source; `robodds components --params plant` prints it). Defaults: the
// member initialisers.
struct PlantParams {
  double wheel_base_m = 0.5;
  model::TwistLimits limits;  // flat keys max_speed_mps, max_turn_rate_radps (not nested)
  model::ActuatorLimits actuator;  // flat keys max_wheel_speed_mps, max_accel_mps2, max_angular_accel_radps2
  double command_timeout_s = 0.5;
  PoseDisturbance disturbance;  // flat keys disturbance_at_s, disturbance_dx_m, ... (not nested)

  /// Throws std::invalid_argument("key: reason").
  void validate() const;
};

const params::ParamTable<PlantParams>& plant_model_param_table();

}  // namespace robodds::plant
