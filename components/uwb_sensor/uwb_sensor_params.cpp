#include "components/uwb_sensor/uwb_sensor_params.hpp"

#include <cmath>
#include <string>

#include "common/number_text.hpp"
#include "common/param_checks.hpp"

namespace robodds::uwb_sensor {

const params::ParamTable<UwbSensorParams>& uwb_sensor_param_table() {
  using P = UwbSensorParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>(
          "UWB array sensor (issue 11, paper 3): K x L node-to-node ranges from each served robot to every other\n"
          "robot of the scenario, r = d + white + link bias (Gauss-Markov) + pair common mode (Gauss-Markov)\n"
          "+ NLOS excess, >= 0; calibration in components/uwb_sensor/README.md.")
          .add("rate_hz", &P::rate_hz, "Hz", params::positive(), "sampling rate; must divide the simulation rate")
          .add("max_range_m", &P::max_range_m, "m", params::positive(),
               "no ranges for a pair whose largest node-to-node range exceeds this (paper: 100)")
          .add("nlos_walls_m", &P::nlos_walls_m, "m",
               params::shown_as(params::any<std::vector<params::Point2>>(), "pairs of finite points, walls >= 1 mm"),
               "walls [[x1, y1], [x2, y2], ...] (world frame, two points each): links crossing one get an NLOS excess every frame")
          .include(&P::errors, uwb_error_param_table());
  return table;
}

void UwbSensorParams::validate() const {
  uwb_sensor_param_table().check_ranges(*this);
  errors.validate();
  if (nlos_walls_m.size() % 2 != 0) {
    param_checks::reject("nlos_walls_m", "must list walls as pairs of end points (an even number of points)",
                         std::to_string(nlos_walls_m.size()) + " points");
  }
  for (std::size_t i = 0; i < nlos_walls_m.size(); ++i) {
    for (double v : nlos_walls_m[i]) {
      if (!std::isfinite(v)) {
        param_checks::reject("nlos_walls_m", "point " + std::to_string(i) + " must be finite", v);
      }
    }
  }
  for (const Wall& wall : walls()) {
    if ((wall.to - wall.from).norm() < 1e-3) {
      param_checks::reject("nlos_walls_m", "a wall must be at least 1 mm long",
                           "[" + shortest_text(wall.from.x()) + ", " + shortest_text(wall.from.y()) + "] to itself");
    }
  }
}

std::vector<Wall> UwbSensorParams::walls() const {
  std::vector<Wall> out;
  for (std::size_t i = 0; i + 1 < nlos_walls_m.size(); i += 2) {
    out.push_back(Wall{Eigen::Vector2d(nlos_walls_m[i][0], nlos_walls_m[i][1]),
                       Eigen::Vector2d(nlos_walls_m[i + 1][0], nlos_walls_m[i + 1][1])});
  }
  return out;
}

}  // namespace robodds::uwb_sensor
