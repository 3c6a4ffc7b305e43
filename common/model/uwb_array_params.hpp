#pragma once
// The UWB array a robot carries, as parameters: one definition of the keys array_side_m and
// nodes_m for the UWB sensor (components/uwb_sensor) and the relative-pose estimator
// (components/uwb_relative_estimator/node): both must describe the same array, or every estimate
// is biased without the cost showing it.
#include <cstddef>
#include <vector>

#include "common/model/uwb_array.hpp"
#include "common/param_table.hpp"

namespace robodds::model {

/// At most this many nodes per array: K x L ranges must fit UwbRanges' sequence<double, 64>.
inline constexpr std::size_t kMaxUwbNodes = 8;

// Units, ranges and one-line descriptions of these fields: uwb_array_param_table(), the one
// source. Defaults: the initialisers.
struct UwbArrayParams {
  /// Used when nodes_m is empty: model::square_array(array_side_m) and its labelling.
  double array_side_m = 0.5;
  /// Explicit node positions (body frame, label = index) instead of the square; every robot
  /// carries the same array. 3 to kMaxUwbNodes nodes, none closer than 1 mm (validate()).
  std::vector<params::Point2> nodes_m;

  /// Throws std::invalid_argument "key: reason (got value)": the table's ranges, then the array
  /// checks (model::check_array) under the key nodes_m.
  void validate() const;
  /// nodes_m, or the square of side array_side_m.
  UwbArray array() const;
};

/// Keys array_side_m and nodes_m (include them into a component's table with include()).
const params::ParamTable<UwbArrayParams>& uwb_array_param_table();

}  // namespace robodds::model
