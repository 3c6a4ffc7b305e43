#pragma once
// Parameters of the simulated wheel odometry of a differential-drive robot.

#include "common/param_table.hpp"

namespace robodds::odometry_sensor {

// Units, ranges and one-line descriptions of these fields: odometry_sensor_param_table() in
// odometry_params.cpp (the one source; `robodds components --params odometry_sensor` prints it).
// Defaults: the member initialisers.
struct OdometryParams {
  /// Used by the node's timer; the model itself is per reading.
  double rate_hz = 50.0;
  /// Zero-mean Gaussian, on each wheel's measured rim speed, drawn independently per wheel and
  /// per reading (not scaled with dt).
  double wheel_speed_noise_std_mps = 0.02;
  /// A systematic scale error (e.g. 0.01 reads 1% fast) that the reading's claimed variance does
  /// not cover.
  double left_slip = 0.0;
  double right_slip = 0.0;
  /// Slip that wanders (an uneven floor: paper 3's wheels "slip and spin to different degrees"):
  /// each wheel's scale error also carries an independent zero-mean Gauss-Markov process of this
  /// stationary standard deviation (dimensionless, like the slips) and correlation time. 0 = off
  /// (and then no random draws are spent on it, so existing streams are unchanged).
  double slip_wander_sigma = 0.0;
  double slip_wander_tau_s = 10.0;
  /// A constant error added to the measured turn rate (like a gyro's bias), on top of what the
  /// wheels give; like the slips, not covered by the reading's claimed variance.
  double turn_rate_bias_radps = 0.0;

  /// Throws std::invalid_argument "key: reason (got value)" for the first bad field; the key is
  /// the field name so the runtime can point at the parameter file that set it.
  void validate() const;
};

/// Every parameter of the odometry_sensor component (config/odometry_sensor.params.yaml is
/// generated from it).
const params::ParamTable<OdometryParams>& odometry_sensor_param_table();

}  // namespace robodds::odometry_sensor
