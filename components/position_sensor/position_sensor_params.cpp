#include "components/position_sensor/position_sensor_params.hpp"

#include "common/param_checks.hpp"

namespace robodds::position_sensor {

void PositionSensorParams::validate() const {
  param_checks::require_positive("rate_hz", rate_hz);
  param_checks::require_non_negative("noise_var_x_m2", noise_var_x_m2);
  param_checks::require_non_negative("noise_var_y_m2", noise_var_y_m2);
}

}  // namespace robodds::position_sensor
