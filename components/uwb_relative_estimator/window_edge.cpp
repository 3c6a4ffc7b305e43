#include "components/uwb_relative_estimator/window_edge.hpp"

#include <cmath>

namespace robodds::uwb_relative_estimator {

WindowEdge::WindowEdge(const model::Pose2& measured, double xy_std_m, double theta_std_rad)
    : measured_(measured),
      xy_std_m_(xy_std_m),
      theta_std_rad_(theta_std_rad),
      xy_std_inverse_(1.0 / xy_std_m),
      theta_std_inverse_(1.0 / theta_std_rad) {}

bool WindowEdge::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const double* a = parameters[0];
  const double* b = parameters[1];
  const double c = std::cos(a[2]);
  const double s = std::sin(a[2]);
  const double dx = b[0] - a[0];
  const double dy = b[1] - a[1];
  const double dtheta = (b[2] - a[2]) - measured_.theta;
  const double sin_d = std::sin(dtheta);
  const double cos_d = std::cos(dtheta);
  const double e_x = (c * dx + s * dy) - measured_.x;
  const double e_y = (-s * dx + c * dy) - measured_.y;
  const double e_theta = std::atan2(sin_d, cos_d);
  if (jacobians == nullptr) {
    // Autodiff ran the functor on plain doubles here: a division.
    residuals[0] = e_x / xy_std_m_;
    residuals[1] = e_y / xy_std_m_;
    residuals[2] = e_theta / theta_std_rad_;
    return true;
  }
  // ... and on Jets there: Jet / Jet multiplies by the inverse.
  residuals[0] = e_x * xy_std_inverse_;
  residuals[1] = e_y * xy_std_inverse_;
  residuals[2] = e_theta * theta_std_inverse_;
  // Derivative k of each intermediate as ceres::Jet forms it from the seeds (the unit vector of
  // parameter k), keeping its multiplications by zero: signed zeros are part of "bit for bit".
  const double tmp = 1.0 / (cos_d * cos_d + sin_d * sin_d);
  const double x_quotient = e_x * xy_std_inverse_;
  const double y_quotient = e_y * xy_std_inverse_;
  const double theta_quotient = e_theta * theta_std_inverse_;
  for (int k = 0; k < 6; ++k) {
    double* block = jacobians[k / 3];
    if (block == nullptr) {
      continue;
    }
    const auto seed = [k](int parameter) { return parameter == k ? 1.0 : 0.0; };  // a: 0-2, b: 3-5
    const double d_dx = seed(3) - seed(0);
    const double d_dy = seed(4) - seed(1);
    const double d_c = -s * seed(2);
    const double d_s = c * seed(2);
    const double d_ab0 = (c * d_dx + d_c * dx) + (s * d_dy + d_s * dy);
    const double d_ab1 = (-s * d_dx + -d_s * dx) + (c * d_dy + d_c * dy);
    const double d_dtheta = (seed(5) - seed(2)) - 0.0;
    const double d_sin = cos_d * d_dtheta;
    const double d_cos = -sin_d * d_dtheta;
    const double d_wrap = tmp * (-sin_d * d_cos + cos_d * d_sin);
    const int column = k % 3;  // row-major 3 x 3: d residual[row] / d parameter[column]
    block[column] = ((d_ab0 - 0.0) - x_quotient * 0.0) * xy_std_inverse_;
    block[3 + column] = ((d_ab1 - 0.0) - y_quotient * 0.0) * xy_std_inverse_;
    block[6 + column] = (d_wrap - theta_quotient * 0.0) * theta_std_inverse_;
  }
  return true;
}

}  // namespace robodds::uwb_relative_estimator
