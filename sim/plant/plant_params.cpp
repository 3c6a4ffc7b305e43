#include "sim/plant/plant_params.hpp"


namespace robodds::plant {

const params::ParamTable<PlantParams>& plant_model_param_table() {
  static const params::ParamTable<PlantParams> table =
      params::ParamTable<PlantParams>()
          .add("wheel_base_m", &PlantParams::wheel_base_m, "m", params::positive(),
               "D in eq. (1): distance between the wheels (WHEEL_SPEEDS commands)")
          .add("max_speed_mps", &PlantParams::limits, &model::TwistLimits::max_speed_mps, "m/s",
               params::non_negative("0 = unlimited"), "|v| limit applied to commands (the paper: 0)")
          .add("max_turn_rate_radps", &PlantParams::limits, &model::TwistLimits::max_turn_rate_radps, "rad/s",
               params::non_negative("0 = unlimited"), "|omega| limit (the paper: 0)")
          .add("command_timeout_s", &PlantParams::command_timeout_s, "s", params::positive(),
               "real time only: a command older than this stops the robot");
  return table;
}

void PlantParams::validate() const { plant_model_param_table().check_ranges(*this); }

}  // namespace robodds::plant
