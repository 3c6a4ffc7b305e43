#pragma once
// Parameters of the simulated absolute position sensor (a GPS-like fix of the robot's x/y).
// Defaults: the member initialisers; keys, units, ranges, descriptions: position_sensor_param_table().

#include "common/param_table.hpp"

namespace robodds::position_sensor {

struct PositionSensorParams {
  /// Fixes per second (Hz). Used by the node's timer; the measurement model itself is per fix.
  double rate_hz = 10.0;
  /// Variance of the independent zero-mean Gaussian noise on each world axis (m^2).
  /// Paper 1, Step 1 uses 2.28 m^2 per axis.
  double noise_var_x_m2 = 2.28;
  double noise_var_y_m2 = 2.28;

  /// Throws std::invalid_argument "key: reason (got value)" for the first bad field; the key is
  /// the field name so the runtime can point at the parameter file that set it.
  void validate() const;
};

/// Every parameter of the position_sensor component (config/position_sensor.params.yaml is
/// generated from it).
const params::ParamTable<PositionSensorParams>& position_sensor_param_table();

}  // namespace robodds::position_sensor
