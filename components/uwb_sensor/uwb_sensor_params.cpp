#include "components/uwb_sensor/uwb_sensor_params.hpp"

#include <string>

#include "common/param_checks.hpp"

namespace robodds::uwb_sensor {

const params::ParamTable<UwbSensorParams>& uwb_sensor_param_table() {
  using P = UwbSensorParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>(
          "UWB array sensor (issue 11, paper 3): K x L node-to-node ranges from each served robot to every other\n"
          "robot of the scenario, r = d + white + link bias (Gauss-Markov) + pair common mode (Gauss-Markov)\n"
          "+ NLOS excess, >= 0; calibration in components/uwb_sensor/README.md.")
          .add("rate_hz", &P::rate_hz, "Hz", params::positive(), "sampling rate; must divide the simulation rate")
          .include(&P::array_params, model::uwb_array_param_table())
          .add("max_range_m", &P::max_range_m, "m", params::positive(),
               "no ranges for a pair whose largest node-to-node range exceeds this (paper: 100)")
          .include(&P::errors, uwb_error_param_table());
  return table;
}

void UwbSensorParams::validate() const {
  uwb_sensor_param_table().check_ranges(*this);
  errors.validate();
  array_params.validate();
}

}  // namespace robodds::uwb_sensor
