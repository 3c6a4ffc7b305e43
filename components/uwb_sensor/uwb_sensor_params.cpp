#include "components/uwb_sensor/uwb_sensor_params.hpp"

#include <string>

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
          .add("array_side_m", &P::array_side_m, "m", params::positive(),
               "side of the square array (paper: 0.3 / 0.5 / 0.7), used when nodes_m is empty")
          .add("nodes_m", &P::nodes_m, "m", params::shown_as(params::any<std::vector<params::Point2>>(), "[] or 3 to 8 nodes"),
               "explicit node positions [x forward, y left] in the body frame, label = index; [] = the square")
          .add("max_range_m", &P::max_range_m, "m", params::positive(),
               "no ranges for a pair whose largest node-to-node range exceeds this (paper: 100)")
          .include(&P::errors, uwb_error_param_table());
  return table;
}

void UwbSensorParams::validate() const {
  uwb_sensor_param_table().check_ranges(*this);
  errors.validate();
  if (nodes_m.empty()) {
    return;  // the square of a positive side: always a valid array
  }
  if (nodes_m.size() > kMaxNodes) {
    param_checks::reject("nodes_m",
                         "must have at most " + std::to_string(kMaxNodes) + " nodes (K x L ranges per sample, at most 64)",
                         std::to_string(nodes_m.size()) + " nodes");
  }
  model::check_array("nodes_m", array());
}

model::UwbArray UwbSensorParams::array() const {
  if (nodes_m.empty()) {
    return model::square_array(array_side_m);
  }
  model::UwbArray out;
  for (const params::Point2& p : nodes_m) {
    out.nodes_m.emplace_back(p[0], p[1]);
  }
  return out;
}

}  // namespace robodds::uwb_sensor
