#include "common/model/pose2.hpp"

#include "common/angle.hpp"
#include "common/number_text.hpp"

namespace robodds::model {

Pose2 compose(const Pose2& a_b, const Pose2& b_c) {
  const double c = std::cos(a_b.theta);
  const double s = std::sin(a_b.theta);
  return {a_b.x + c * b_c.x - s * b_c.y, a_b.y + s * b_c.x + c * b_c.y, wrap_angle(a_b.theta + b_c.theta)};
}

Pose2 between(const Pose2& w_a, const Pose2& w_b) {
  const double a[3] = {w_a.x, w_a.y, w_a.theta};
  const double b[3] = {w_b.x, w_b.y, w_b.theta};
  double a_b[3];
  between_unwrapped(a, b, a_b);
  return {a_b[0], a_b[1], wrap_angle(a_b[2])};
}

std::string to_text(const Pose2& pose) {
  return "x=" + shortest_text(pose.x) + ", y=" + shortest_text(pose.y) + ", theta=" + shortest_text(pose.theta);
}

}  // namespace robodds::model
