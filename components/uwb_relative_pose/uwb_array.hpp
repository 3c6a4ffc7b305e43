#pragma once
// UWB antenna arrays of paper 3 (Liu et al. 2022): each robot carries K nodes at known positions
// in its body frame (x forward, y left, metres, origin at the robot centre).

#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace robodds::uwb {

struct UwbArray {
  std::vector<Eigen::Vector2d> nodes_m;  // body frame, m; the index is the node's label
};

/// The paper's square array of side `side_m` (0.3 / 0.5 / 0.7 m), centred on the robot. Labels go
/// counter-clockwise from the front-left corner: 0 (+s/2, +s/2), 1 (-s/2, +s/2), 2 (-s/2, -s/2),
/// 3 (+s/2, -s/2). Both robots must use the same convention: a label shifted by one on one robot
/// turns every estimate by 90 degrees without raising the cost (tested).
/// Throws std::invalid_argument unless side_m > 0 and finite.
UwbArray square_array(double side_m);

/// Nodes closer than this count as coincident (m).
inline constexpr double kMinNodeSeparationM = 1e-3;

/// Refuses an array the relative pose cannot use: fewer than 3 nodes, a non-finite position, or two
/// nodes closer than kMinNodeSeparationM. Throws std::invalid_argument "key: reason (got ...)",
/// naming `key` (the parameter that set the array, e.g. the node's YAML key).
void validate_array(const UwbArray& array, std::string_view key);

}  // namespace robodds::uwb
