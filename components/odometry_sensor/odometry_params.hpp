#pragma once
// Parameters of the simulated wheel odometry of a differential-drive robot.
// Defaults: the member initialisers; keys, units, ranges, descriptions: odometry_sensor_param_table().

#include "common/param_table.hpp"

namespace robodds::odometry_sensor {

struct OdometryParams {
  /// Readings per second (Hz). Used by the node's timer; the model itself is per reading.
  double rate_hz = 50.0;
  /// Distance between the two wheels' contact points (m); converts between twist and wheel speeds.
  double wheel_base_m = 0.5;
  /// Standard deviation (m/s) of the zero-mean white Gaussian noise added to each wheel's
  /// measured rim speed, independently per wheel and per reading (not scaled with dt).
  double wheel_speed_noise_std_mps = 0.02;
  /// Fractional scale error of each wheel's measured speed: measured = (1 + slip) * true,
  /// e.g. 0.01 reads 1% fast. A systematic error the reading's claimed variance does not cover.
  /// Must lie in (-0.5, 0.5).
  double left_slip = 0.0;
  double right_slip = 0.0;

  /// Throws std::invalid_argument "key: reason (got value)" for the first bad field; the key is
  /// the field name so the runtime can point at the parameter file that set it.
  void validate() const;
};

/// Every parameter of the odometry_sensor component (config/odometry_sensor.params.yaml is
/// generated from it).
const params::ParamTable<OdometryParams>& odometry_sensor_param_table();

}  // namespace robodds::odometry_sensor
