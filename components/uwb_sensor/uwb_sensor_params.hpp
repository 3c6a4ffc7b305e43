#pragma once
// Parameters of the simulated UWB array sensor (issue 11, paper 3): the array every robot
// carries, the rate and range of the sensor, and the error model (uwb_error_model.hpp).

#include <cstddef>
#include <vector>

#include "common/model/uwb_array.hpp"
#include "common/param_table.hpp"
#include "components/uwb_sensor/uwb_error_model.hpp"

namespace robodds::uwb_sensor {

/// At most this many nodes per array: K x L ranges must fit UwbRanges' sequence<double, 64>.
inline constexpr std::size_t kMaxNodes = 8;

// Units, ranges and one-line descriptions of these fields: uwb_sensor_param_table(), the one
// source (`robodds components --params uwb_sensor` prints it). Defaults: the initialisers.
struct UwbSensorParams {
  double rate_hz = 50.0;
  /// Used when nodes_m is empty: model::square_array(array_side_m), the labelling the estimator
  /// (components/uwb_relative_pose) assumes.
  double array_side_m = 0.5;
  /// Explicit node positions (body frame, label = index) instead of the square; every robot
  /// carries the same array. 3 to kMaxNodes nodes, none closer than 1 mm (validate()).
  std::vector<params::Point2> nodes_m;
  /// A pair whose largest node-to-node range exceeds this gets no ranges (an empty sample in
  /// lockstep).
  double max_range_m = 100.0;
  UwbErrorParams errors;

  /// Throws std::invalid_argument "key: reason (got value)" for the first bad field, including
  /// the array checks (model::check_array) under the key nodes_m or array_side_m.
  void validate() const;

  /// The array every robot carries: nodes_m, or the square of side array_side_m.
  model::UwbArray array() const;
};

const params::ParamTable<UwbSensorParams>& uwb_sensor_param_table();

}  // namespace robodds::uwb_sensor
