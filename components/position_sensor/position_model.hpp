#pragma once
// Measurement model of the absolute position sensor: the true world-frame position plus
// independent zero-mean Gaussian noise on x and y (paper 1, Step 1), and optionally outliers: with
// probability outlier_probability a fix is moved by outlier_offset_m along world +x. Heading is
// not measured.

#include "common/model/pose2.hpp"
#include "common/random.hpp"
#include "components/position_sensor/position_sensor_params.hpp"

namespace robodds::position_sensor {

/// One noisy position fix, world frame.
struct PositionFix {
  double x = 0.0;      // m
  double y = 0.0;      // m
  double var_x = 0.0;  // m^2, the noise variance the sensor claims for x (= the configured one)
  double var_y = 0.0;  // m^2, same for y
};

/// Samples one fix of `truth` (only x and y are used). Always draws exactly two standard
/// normals from `engine` (x first, then y), also when a variance is zero, so the stream
/// position does not depend on the noise; then one uniform01 for the outlier decision only when
/// outlier_probability > 0. `params` must have passed validate().
PositionFix measure_position(const model::Pose2& truth, const PositionSensorParams& params,
                             RandomEngine& engine);

}  // namespace robodds::position_sensor
