#pragma once
// Walls that block the line of sight between UWB nodes (paper 3's experiment 1-b: a wooden board
// between the robots). A link whose straight node-to-node segment crosses a wall measures with a
// non-line-of-sight excess at every frame (uwb_error_model.hpp, measure_ranges).

#include <Eigen/Core>
#include <vector>

#include "common/model/pose2.hpp"
#include "common/model/uwb_array.hpp"

namespace robodds::uwb_sensor {

/// A straight wall in the world frame, m.
struct Wall {
  Eigen::Vector2d from;
  Eigen::Vector2d to;
};

/// K x L flags, true where link (k, l) is blocked; empty (0 x 0) means nothing is blocked.
using BlockedLinks = Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>;

/// Whether the closed segments p1-p2 and q1-q2 share a point (touching counts: a link grazing a
/// wall's end is blocked).
bool segments_cross(const Eigen::Vector2d& p1, const Eigen::Vector2d& p2, const Eigen::Vector2d& q1,
                    const Eigen::Vector2d& q2);

/// For robot a at `pose_a` measuring robot b at `pose_b` (world frame): which node-to-node links
/// (row k: node k of a, column l: node l of b) cross any of `walls`. No walls: an empty matrix.
BlockedLinks links_through_walls(const model::UwbArray& a, const model::Pose2& pose_a, const model::UwbArray& b,
                                 const model::Pose2& pose_b, const std::vector<Wall>& walls);

}  // namespace robodds::uwb_sensor
