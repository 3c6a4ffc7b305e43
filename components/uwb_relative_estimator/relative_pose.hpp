#pragma once
// The range that a relative pose of robot j in the body frame of robot i (model::Pose2) predicts
// between a node of i and a node of j: d(x, C_i^k, C_j^l) of paper 3, eq. (1).

#include <cmath>

#include <Eigen/Core>

#include "common/model/pose2.hpp"

namespace robodds::uwb_relative_estimator {

/// Distance between node `node_i` of robot i and node `node_j` of robot j (both in their own body
/// frames, m) when j is at pose (x, y, theta) in i's frame. Templated so that Ceres can
/// differentiate it (T = double or a Jet).
template <class T>
T predicted_range(const T& x, const T& y, const T& theta, const Eigen::Vector2d& node_i, const Eigen::Vector2d& node_j) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T c = cos(theta);
  const T s = sin(theta);
  const T dx = x + c * node_j.x() - s * node_j.y() - node_i.x();
  const T dy = y + s * node_j.x() + c * node_j.y() - node_i.y();
  return sqrt(dx * dx + dy * dy);
}

/// The same for a pose of robot j in robot i's body frame (model::Pose2: m, m, rad CCW).
inline double predicted_range(const model::Pose2& pose, const Eigen::Vector2d& node_i, const Eigen::Vector2d& node_j) {
  return predicted_range(pose.x, pose.y, pose.theta, node_i, node_j);
}

/// predicted_range() with the parts an analytic Jacobian needs, for j at (x, y) m in i's frame with
/// heading cosine `c` and sine `s` (taken once per pose by the caller): node_j rotated into i's frame
/// (rx, ry), the vector from node_i to it (dx, dy) and its length d (m). d/d(x, y) = (dx, dy) / d,
/// d/dtheta = (-dx ry + dy rx) / d. Rounds as (x + rx) - node_i.x, so d may differ from
/// predicted_range()'s in the last bit. The one geometry of eq. (1)'s and the tc window's solvers.
struct NodePairGeometry {
  double rx, ry, dx, dy, d;
};
inline NodePairGeometry node_pair_geometry(double x, double y, double c, double s, const Eigen::Vector2d& node_i,
                                           const Eigen::Vector2d& node_j) {
  NodePairGeometry g;
  g.rx = c * node_j.x() - s * node_j.y();
  g.ry = s * node_j.x() + c * node_j.y();
  g.dx = x + g.rx - node_i.x();
  g.dy = y + g.ry - node_i.y();
  g.d = std::sqrt(g.dx * g.dx + g.dy * g.dy);
  return g;
}

}  // namespace robodds::uwb_relative_estimator
