#include "sim/plant/plant_model_params.hpp"


namespace robodds::plant {

const params::ParamTable<PlantParams>& plant_model_param_table() {
  static const params::ParamTable<PlantParams> table =
      params::ParamTable<PlantParams>()
          .add("command_timeout_s", &PlantParams::command_timeout_s, "s", params::positive(),
               "real time only: a command older than this stops the robot")
          .add("disturbance_at_s", &PlantParams::disturbance, &PoseDisturbance::at_s, "s",
               params::shown_as(params::finite(), "finite (< 0 = off)"),
               "kidnapped robot: at this simulated time the true pose of every robot jumps once (< 0 = never)")
          .add("disturbance_dx_m", &PlantParams::disturbance, &PoseDisturbance::dx_m, "m", params::finite(),
               "the jump along world x")
          .add("disturbance_dy_m", &PlantParams::disturbance, &PoseDisturbance::dy_m, "m", params::finite(),
               "the jump along world y")
          .add("disturbance_dtheta_rad", &PlantParams::disturbance, &PoseDisturbance::dtheta_rad, "rad", params::finite(),
               "the jump of the heading (counter-clockwise)");
  return table;
}

void PlantParams::validate() const { plant_model_param_table().check_ranges(*this); }

}  // namespace robodds::plant
