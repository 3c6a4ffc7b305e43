#include "components/uwb_relative_pose/relative_pose.hpp"

#include "common/angle.hpp"
#include "common/number_text.hpp"

namespace robodds::uwb {

RelativePose compose(const RelativePose& a_b, const RelativePose& b_c) {
  const double c = std::cos(a_b.theta_rad);
  const double s = std::sin(a_b.theta_rad);
  return {a_b.x_m + c * b_c.x_m - s * b_c.y_m, a_b.y_m + s * b_c.x_m + c * b_c.y_m,
          wrap_angle(a_b.theta_rad + b_c.theta_rad)};
}

RelativePose between(const RelativePose& w_a, const RelativePose& w_b) {
  const double a[3] = {w_a.x_m, w_a.y_m, w_a.theta_rad};
  const double b[3] = {w_b.x_m, w_b.y_m, w_b.theta_rad};
  double a_b[3];
  between_unwrapped(a, b, a_b);
  return {a_b[0], a_b[1], wrap_angle(a_b[2])};
}

std::string to_text(const RelativePose& pose) {
  return "x=" + shortest_text(pose.x_m) + ", y=" + shortest_text(pose.y_m) + ", theta=" + shortest_text(pose.theta_rad);
}

}  // namespace robodds::uwb
