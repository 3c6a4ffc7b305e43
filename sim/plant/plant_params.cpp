#include "sim/plant/plant_params.hpp"

#include "common/param_checks.hpp"

namespace robodds::plant {

void PlantParams::validate() const {
  param_checks::require_positive("wheel_base_m", wheel_base_m);
  param_checks::require_non_negative("max_speed_mps", limits.max_speed_mps, "0 = unlimited");
  param_checks::require_non_negative("max_turn_rate_radps", limits.max_turn_rate_radps, "0 = unlimited");
  param_checks::require_positive("command_timeout_s", command_timeout_s);
}

}  // namespace robodds::plant
