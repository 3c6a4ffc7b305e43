#include "sim/plant/plant_params.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace robodds::plant {

void PlantParams::validate() const {
  if (!(wheel_base_m > 0.0) || !std::isfinite(wheel_base_m)) {
    throw std::invalid_argument("wheel_base_m: must be > 0 (got " + std::to_string(wheel_base_m) + ")");
  }
  if (!(limits.max_speed_mps >= 0.0)) {
    throw std::invalid_argument("max_speed_mps: must be >= 0, 0 = unlimited (got " + std::to_string(limits.max_speed_mps) + ")");
  }
  if (!(limits.max_turn_rate_radps >= 0.0)) {
    throw std::invalid_argument("max_turn_rate_radps: must be >= 0, 0 = unlimited (got " +
                                std::to_string(limits.max_turn_rate_radps) + ")");
  }
  if (!(command_timeout_s > 0.0)) {
    throw std::invalid_argument("command_timeout_s: must be > 0 (got " + std::to_string(command_timeout_s) + ")");
  }
}

}  // namespace robodds::plant
