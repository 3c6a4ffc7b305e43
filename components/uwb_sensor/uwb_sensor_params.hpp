#pragma once
// Parameters of the simulated UWB array sensor (issue 11, paper 3): the array every robot
// carries, the rate and range of the sensor, and the error model (uwb_error_model.hpp).

#include <cstddef>
#include <vector>

#include "common/model/uwb_array.hpp"
#include "common/model/uwb_array_params.hpp"
#include "common/param_table.hpp"
#include "components/uwb_sensor/uwb_error_model.hpp"
#include "components/uwb_sensor/uwb_walls.hpp"

namespace robodds::uwb_sensor {

// Units, ranges and one-line descriptions of these fields: uwb_sensor_param_table(), the one
// source (`robodds components --params uwb_sensor` prints it). Defaults: the initialisers.
struct UwbSensorParams {
  double rate_hz = 50.0;
  /// array_side_m, nodes_m (common/model/uwb_array_params.hpp: the estimator reads the same keys).
  model::UwbArrayParams array_params;
  /// A pair whose largest node-to-node range exceeds this gets no ranges (an empty sample in
  /// lockstep).
  double max_range_m = 100.0;
  /// Walls (world frame, m) as pairs of end points [[x1, y1], [x2, y2], ...]: a link whose
  /// node-to-node segment crosses one measures with an NLOS excess (nlos_min_m..nlos_max_m) at
  /// every frame (experiment 1-b's board). [] = open space.
  std::vector<params::Point2> nlos_walls_m;
  UwbErrorParams errors;

  /// Throws std::invalid_argument "key: reason (got value)" for the first bad field, including
  /// the array checks (model::check_array) under the key nodes_m or array_side_m.
  void validate() const;

  /// The array every robot carries: nodes_m, or the square of side array_side_m.
  model::UwbArray array() const { return array_params.array(); }
  /// nlos_walls_m as walls (after validate(): an even count of finite points, no wall shorter than 1 mm).
  std::vector<Wall> walls() const;
};

const params::ParamTable<UwbSensorParams>& uwb_sensor_param_table();

}  // namespace robodds::uwb_sensor
