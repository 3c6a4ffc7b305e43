#pragma once
// Parameters of the simulated UWB array sensor (issue 11, paper 3): the rate and range of the
// sensor, the walls, and the error model (uwb_error_model.hpp). The array every robot carries is
// not among them: it is the scenario's shared fact `facts: uwb_array:` (system/robot_facts.hpp).

#include <cstddef>
#include <vector>

#include "common/param_table.hpp"
#include "components/uwb_sensor/uwb_error_model.hpp"
#include "components/uwb_sensor/uwb_walls.hpp"

namespace robodds::uwb_sensor {

// Units, ranges and one-line descriptions of these fields: uwb_sensor_param_table(), the one
// source (`robodds components --params uwb_sensor` prints it). Defaults: the initialisers.
struct UwbSensorParams {
  double rate_hz = 50.0;
  /// A pair whose largest node-to-node range exceeds this gets no ranges (an empty sample in
  /// lockstep).
  double max_range_m = 100.0;
  /// Walls (world frame, m) as pairs of end points [[x1, y1], [x2, y2], ...]: a link whose
  /// node-to-node segment crosses one measures with an NLOS excess (nlos_min_m..nlos_max_m) at
  /// every frame (experiment 1-b's board). [] = open space.
  std::vector<params::Point2> nlos_walls_m;
  UwbErrorParams errors;

  /// Throws std::invalid_argument "key: reason (got value)" for the first bad field.
  void validate() const;

  /// nlos_walls_m as walls (after validate(): an even count of finite points, no wall shorter than 1 mm).
  std::vector<Wall> walls() const;
};

const params::ParamTable<UwbSensorParams>& uwb_sensor_param_table();

}  // namespace robodds::uwb_sensor
