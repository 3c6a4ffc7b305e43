#pragma once
// Plant parameters. Defaults: the member initialisers; keys, units, ranges, descriptions:
// plant_model_param_table().
#include "common/model/twist.hpp"
#include "common/param_table.hpp"

namespace robodds::plant {

struct PlantParams {
  double wheel_base_m = 0.5;       // m, D of eq. (1)
  model::TwistLimits limits;       // m/s, rad/s; 0 = unlimited
  double command_timeout_s = 0.5;  // s, real time: older commands stop the robot

  /// Throws std::invalid_argument("key: reason").
  void validate() const;
};

const params::ParamTable<PlantParams>& plant_model_param_table();

}  // namespace robodds::plant
