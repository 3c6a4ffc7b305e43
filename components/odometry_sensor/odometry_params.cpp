#include "components/odometry_sensor/odometry_params.hpp"

#include "common/param_checks.hpp"

namespace robodds::odometry_sensor {

void OdometryParams::validate() const {
  param_checks::require_positive("rate_hz", rate_hz);
  param_checks::require_positive("wheel_base_m", wheel_base_m);
  param_checks::require_non_negative("wheel_speed_noise_std_mps", wheel_speed_noise_std_mps);
  param_checks::require_in_open_interval("left_slip", left_slip, -0.5, 0.5);
  param_checks::require_in_open_interval("right_slip", right_slip, -0.5, 0.5);
}

}  // namespace robodds::odometry_sensor
