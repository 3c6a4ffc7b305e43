#pragma once
// Relative pose of robot j in the body frame of robot i, and the range it predicts between a node
// of i and a node of j: d(x, C_i^k, C_j^l) of paper 3, eq. (1).

#include <cmath>
#include <string>

#include <Eigen/Core>

namespace robodds::uwb {

/// Pose of robot j in robot i's body frame: position (m) and heading (rad, CCW, in (-pi, pi]).
struct RelativePose {
  double x_m = 0.0;
  double y_m = 0.0;
  double theta_rad = 0.0;
};

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

/// Frame b given in frame a, composed with frame c given in frame b: frame c in frame a.
RelativePose compose(const RelativePose& a_b, const RelativePose& b_c);

/// Frame b in frame a from both given in a common frame w, as {x, y, theta} arrays, with the
/// heading difference not wrapped. Templated so that Ceres can differentiate it (T = double or Jet).
template <class T>
void between_unwrapped(const T* w_a, const T* w_b, T* a_b) {
  using std::cos;
  using std::sin;
  const T c = cos(w_a[2]);
  const T s = sin(w_a[2]);
  const T dx = w_b[0] - w_a[0];
  const T dy = w_b[1] - w_a[1];
  a_b[0] = c * dx + s * dy;
  a_b[1] = -s * dx + c * dy;
  a_b[2] = w_b[2] - w_a[2];
}

/// Frame b in frame a, given both in a common frame w: inverse(w_a) composed with w_b.
RelativePose between(const RelativePose& w_a, const RelativePose& w_b);

/// "x=1.5, y=-2, theta=0.3" (shortest text of each value), for error messages.
std::string to_text(const RelativePose& pose);

inline double predicted_range(const RelativePose& pose, const Eigen::Vector2d& node_i, const Eigen::Vector2d& node_j) {
  return predicted_range(pose.x_m, pose.y_m, pose.theta_rad, node_i, node_j);
}

}  // namespace robodds::uwb
