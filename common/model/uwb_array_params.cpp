#include "common/model/uwb_array_params.hpp"

#include <string>

#include "common/param_checks.hpp"

namespace robodds::model {

const params::ParamTable<UwbArrayParams>& uwb_array_param_table() {
  using P = UwbArrayParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>("The UWB array every robot carries (paper 3).")
          .add("array_side_m", &P::array_side_m, "m", params::positive(),
               "side of the square array (paper: 0.3 / 0.5 / 0.7), used when nodes_m is empty")
          .add("nodes_m", &P::nodes_m, "m", params::shown_as(params::any<std::vector<params::Point2>>(), "[] or 3 to 8 nodes"),
               "explicit node positions [x forward, y left] in the body frame, label = index; [] = the square");
  return table;
}

void UwbArrayParams::validate() const {
  uwb_array_param_table().check_ranges(*this);
  if (nodes_m.empty()) {
    return;  // the square of a positive side: always a valid array
  }
  if (nodes_m.size() > kMaxUwbNodes) {
    param_checks::reject("nodes_m",
                         "must have at most " + std::to_string(kMaxUwbNodes) + " nodes (K x L ranges per sample, at most 64)",
                         std::to_string(nodes_m.size()) + " nodes");
  }
  check_array("nodes_m", array());
}

UwbArray UwbArrayParams::array() const {
  if (nodes_m.empty()) {
    return square_array(array_side_m);
  }
  UwbArray out;
  for (const params::Point2& p : nodes_m) {
    out.nodes_m.emplace_back(p[0], p[1]);
  }
  return out;
}

}  // namespace robodds::model
