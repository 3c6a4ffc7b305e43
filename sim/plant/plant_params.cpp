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
          .add("max_wheel_speed_mps", &PlantParams::actuator, &model::ActuatorLimits::max_wheel_speed_mps, "m/s",
               params::non_negative("0 = unlimited"),
               "each wheel's |rim speed| is clamped on its own, as a motor driver does (bends the path; the paper: 0)")
          .add("max_accel_mps2", &PlantParams::actuator, &model::ActuatorLimits::max_accel_mps2, "m/s^2",
               params::non_negative("0 = unlimited"),
               "|dv/dt| of the applied twist; a safe stop (no or a stale command) is immediate (the paper: 0)")
          .add("max_angular_accel_radps2", &PlantParams::actuator, &model::ActuatorLimits::max_angular_accel_radps2,
               "rad/s^2", params::non_negative("0 = unlimited"),
               "|domega/dt| of the applied twist; the change of (v, omega) is scaled as one (the paper: 0)")
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
