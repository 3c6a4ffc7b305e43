#include "components/position_sensor/position_sensor_params.hpp"


namespace robodds::position_sensor {

const params::ParamTable<PositionSensorParams>& position_sensor_param_table() {
  static const params::ParamTable<PositionSensorParams> table =
      params::ParamTable<PositionSensorParams>(
          "Absolute position sensor (paper 1, Step 1): true position + independent Gaussian noise,\n"
          "optionally with outliers (a fixed x offset with a given probability).")
          .add("rate_hz", &PositionSensorParams::rate_hz, "Hz", params::positive(),
               "sampling rate; must divide the simulation rate")
          .add("noise_var_x_m2", &PositionSensorParams::noise_var_x_m2, "m^2", params::non_negative(),
               "noise variance along x (paper 1: 2.28)")
          .add("noise_var_y_m2", &PositionSensorParams::noise_var_y_m2, "m^2", params::non_negative(),
               "noise variance along y")
          .add("outlier_probability", &PositionSensorParams::outlier_probability, "", params::in_half_open_interval(0.0, 1.0),
               "probability that a fix is an outlier, moved by outlier_offset_m along world +x; 0 = none")
          .add("outlier_offset_m", &PositionSensorParams::outlier_offset_m, "m", params::finite(),
               "x offset of an outlier fix, world frame (negative: along -x)");
  return table;
}

void PositionSensorParams::validate() const { position_sensor_param_table().check_ranges(*this); }

}  // namespace robodds::position_sensor
