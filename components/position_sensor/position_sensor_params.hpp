#pragma once
// Parameters of the simulated absolute position sensor (a GPS-like fix of the robot's x/y).

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

}  // namespace robodds::position_sensor
