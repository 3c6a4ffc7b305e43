#include "components/uwb_sensor/uwb_walls.hpp"

#include <algorithm>

namespace robodds::uwb_sensor {
namespace {

/// Twice the signed area of the triangle (a, b, c): > 0 counter-clockwise, 0 collinear.
double turn(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

/// For c collinear with a-b: whether c lies within the segment's bounding box (so on it).
bool on_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= c.y() &&
         c.y() <= std::max(a.y(), b.y());
}

int sign(double v) { return (v > 0.0) - (v < 0.0); }

}  // namespace

bool segments_cross(const Eigen::Vector2d& p1, const Eigen::Vector2d& p2, const Eigen::Vector2d& q1,
                    const Eigen::Vector2d& q2) {
  const int d1 = sign(turn(q1, q2, p1));
  const int d2 = sign(turn(q1, q2, p2));
  const int d3 = sign(turn(p1, p2, q1));
  const int d4 = sign(turn(p1, p2, q2));
  if (d1 * d2 < 0 && d3 * d4 < 0) {
    return true;  // proper crossing
  }
  return (d1 == 0 && on_segment(q1, q2, p1)) || (d2 == 0 && on_segment(q1, q2, p2)) ||
         (d3 == 0 && on_segment(p1, p2, q1)) || (d4 == 0 && on_segment(p1, p2, q2));
}

BlockedLinks links_through_walls(const model::UwbArray& a, const model::Pose2& pose_a, const model::UwbArray& b,
                                 const model::Pose2& pose_b, const std::vector<Wall>& walls) {
  if (walls.empty()) {
    return BlockedLinks();
  }
  const auto rows = static_cast<Eigen::Index>(a.nodes_m.size());
  const auto cols = static_cast<Eigen::Index>(b.nodes_m.size());
  BlockedLinks blocked = BlockedLinks::Constant(rows, cols, false);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const Eigen::Vector2d from = model::node_in_world(pose_a, a.nodes_m[static_cast<std::size_t>(k)]);
    for (Eigen::Index l = 0; l < cols; ++l) {
      const Eigen::Vector2d to = model::node_in_world(pose_b, b.nodes_m[static_cast<std::size_t>(l)]);
      blocked(k, l) = std::any_of(walls.begin(), walls.end(),
                                  [&](const Wall& w) { return segments_cross(from, to, w.from, w.to); });
    }
  }
  return blocked;
}

}  // namespace robodds::uwb_sensor
