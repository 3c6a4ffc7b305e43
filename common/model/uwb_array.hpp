#pragma once
// UWB antenna arrays of paper 3 (Liu et al. 2022): each robot carries K nodes at known positions
// in its body frame (x forward, y left, metres, origin at the robot centre). One definition for
// the UWB sensor (components/uwb_sensor) and the relative-pose estimator
// (components/uwb_relative_estimator): both must agree on the node labels.

#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "common/model/pose2.hpp"

namespace robodds::model {

struct UwbArray {
  std::vector<Eigen::Vector2d> nodes_m;  // body frame, m; the index is the node's label
};

/// Two nodes closer than this are one node (check_array refuses them).
inline constexpr double kMinNodeSpacingM = 1e-3;

/// The paper's square array of side `side_m` (0.3 / 0.5 / 0.7 m), centred on the robot. Labels go
/// counter-clockwise from the front-left corner: 0 (+s/2, +s/2), 1 (-s/2, +s/2), 2 (-s/2, -s/2),
/// 3 (+s/2, -s/2). Both robots must use the same convention: a label shifted by one on one robot
/// turns every estimate by 90 degrees without raising the cost (tested in uwb_relative_pose).
/// Throws std::invalid_argument("side_m: ...") unless side_m > 0 and finite.
UwbArray square_array(double side_m);

/// Throws std::invalid_argument("<key>: ...") unless the array has at least 3 nodes (a relative
/// heading needs them), every coordinate is finite and no two nodes are closer than
/// kMinNodeSpacingM. `key` names the parameter the array came from.
void check_array(std::string_view key, const UwbArray& array);

/// Node `node_m` of a robot at `pose` (world frame), in the world frame.
Eigen::Vector2d node_in_world(const Pose2& pose, const Eigen::Vector2d& node_m);

/// The true K x L ranges (m) between the nodes of robot a (array `a` at `pose_a`, row k: node k)
/// and those of robot b (`b` at `pose_b`, column l: node l); poses in one common frame.
Eigen::MatrixXd array_ranges(const UwbArray& a, const Pose2& pose_a, const UwbArray& b, const Pose2& pose_b);

}  // namespace robodds::model
