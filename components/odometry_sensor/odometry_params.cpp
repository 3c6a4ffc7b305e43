#include "components/odometry_sensor/odometry_params.hpp"

#include "common/param_checks.hpp"

namespace robodds::odometry_sensor {

void OdometryParams::validate() const {
  param_checks::require_positive("rate_hz", rate_hz);
  param_checks::require_positive("wheel_base_m", wheel_base_m);
  param_checks::require_non_negative("wheel_speed_noise_std_mps", wheel_speed_noise_std_mps);
  for (const auto& [key, slip] : {std::pair{"left_slip", left_slip}, std::pair{"right_slip", right_slip}}) {
    if (!(slip > -0.5 && slip < 0.5)) {  // NaN fails too
      param_checks::reject(key, "must be in (-0.5, 0.5)", slip);
    }
  }
}

}  // namespace robodds::odometry_sensor
