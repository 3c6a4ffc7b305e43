#pragma once
// A planar pose and the 2-D pose algebra on it. Pure maths: SI units, x/y in m, heading theta in
// rad counter-clockwise from +x. The frame is the one the caller says: the world frame for a robot's
// pose (paper 1), another robot's body frame for a relative pose (paper 3).

#include <cmath>
#include <string>

namespace robodds::model {

struct Pose2 {
  double x = 0.0;      // m
  double y = 0.0;      // m
  double theta = 0.0;  // rad, (-pi, pi]
};

/// Frame b given in frame a, composed with frame c given in frame b: frame c in frame a.
Pose2 compose(const Pose2& a_b, const Pose2& b_c);

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
Pose2 between(const Pose2& w_a, const Pose2& w_b);

/// "x=1.5, y=-2, theta=0.3" (shortest text of each value), for error messages.
std::string to_text(const Pose2& pose);

}  // namespace robodds::model
