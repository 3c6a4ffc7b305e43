#include "components/uwb_relative_pose/relative_pose.hpp"

#include "common/angle.hpp"

namespace robodds::uwb {

RelativePose compose(const RelativePose& a_b, const RelativePose& b_c) {
  const double c = std::cos(a_b.theta_rad);
  const double s = std::sin(a_b.theta_rad);
  return {a_b.x_m + c * b_c.x_m - s * b_c.y_m, a_b.y_m + s * b_c.x_m + c * b_c.y_m,
          wrap_angle(a_b.theta_rad + b_c.theta_rad)};
}

RelativePose between(const RelativePose& w_a, const RelativePose& w_b) {
  const double c = std::cos(w_a.theta_rad);
  const double s = std::sin(w_a.theta_rad);
  const double dx = w_b.x_m - w_a.x_m;
  const double dy = w_b.y_m - w_a.y_m;
  return {c * dx + s * dy, -s * dx + c * dy, wrap_angle(w_b.theta_rad - w_a.theta_rad)};
}

}  // namespace robodds::uwb
