#pragma once
// Measurement model of paper 2's range sensor: the true distance from the robot to its target
// plus zero-mean Gaussian noise, clamped at 0 (a range is never negative), or a dropout.

#include "common/random.hpp"
#include "components/range_sensor/range_sensor_params.hpp"

namespace robodds::range_sensor {

/// The true distance (m) between (x, y) and (target_x, target_y), world frame.
double true_range(double x, double y, double target_x, double target_y);

/// One reading of `truth_m` (m) with noise, clamped at 0. Always draws exactly one standard
/// normal, also when the noise is zero, so the stream does not depend on the configuration.
/// `params` must have passed validate().
double measure_range(double truth_m, const RangeSensorParams& params, RandomEngine& engine);

/// Whether a sample is lost (probability dropout_probability). Always draws exactly one uniform.
/// A stream of its own: the sensor decides a sample's fate when it announces the sample
/// (next_step), before it measures it.
bool sample_lost(const RangeSensorParams& params, RandomEngine& engine);

}  // namespace robodds::range_sensor
