#pragma once
// Parameters of the simulated absolute position sensor (a GPS-like fix of the robot's x/y).

#include "common/param_table.hpp"

namespace robodds::position_sensor {

// Units, ranges and one-line descriptions of these fields: position_sensor_param_table(), the one
// source (`robodds components --params position_sensor` prints it). Defaults: the initialisers.
struct PositionSensorParams {
  /// Used by the node's timer; the measurement model itself is per fix.
  double rate_hz = 10.0;
  /// Of independent zero-mean Gaussian noise on each world axis.
  double noise_var_x_m2 = 2.28;
  double noise_var_y_m2 = 2.28;
  /// Outliers (a multipath-like fault): with this probability a fix is moved by
  /// outlier_offset_m along world +x (a negative offset moves it along -x), on top of its noise.
  /// 0 = none; the fix's claimed variance does not change.
  double outlier_probability = 0.0;
  double outlier_offset_m = 30.0;

  /// Throws std::invalid_argument "key: reason (got value)" for the first bad field; the key is
  /// the field name so the runtime can point at the parameter file that set it.
  void validate() const;
};

/// Every parameter of the position_sensor component (config/position_sensor.params.yaml is
/// generated from it).
const params::ParamTable<PositionSensorParams>& position_sensor_param_table();

}  // namespace robodds::position_sensor
