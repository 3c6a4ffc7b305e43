#pragma once
// Parameters of the simulated range sensor of paper 2: the distance from a robot to its target.

#include "common/param_table.hpp"

namespace robodds::range_sensor {

// Units, ranges and one-line descriptions of these fields: range_sensor_param_table(), the one
// source (`robodds components --params range_sensor` prints it). Defaults: the initialisers.
struct RangeSensorParams {
  double rate_hz = 50.0;
  /// Standard deviation of the zero-mean Gaussian noise on each range (issue 10 runs 0 and 0.5 m).
  double noise_sigma_m = 0.5;
  /// Each sample is lost with this probability, independently (0 = none).
  double dropout_probability = 0.0;

  /// Throws std::invalid_argument "key: reason (got value)" for the first bad field.
  void validate() const;
};

const params::ParamTable<RangeSensorParams>& range_sensor_param_table();

}  // namespace robodds::range_sensor
