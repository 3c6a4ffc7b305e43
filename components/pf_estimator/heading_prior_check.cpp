#include "components/pf_estimator/heading_prior_check.hpp"

#include <cmath>

#include "common/angle.hpp"
#include "common/model/diff_drive_kinematics.hpp"

namespace robodds::pf_estimator {

void HeadingPriorCheck::start(double prior_theta_rad) {
  verdict_ = tolerance_rad_ > 0.0 ? Verdict::kPending : Verdict::kConfirmed;
  dr_x_ = 0.0;
  dr_y_ = 0.0;
  dr_theta_ = prior_theta_rad;
  fixes_ = 0;
  first_fx_ = first_fy_ = first_dx_ = first_dy_ = 0.0;
  angle_error_rad_ = 0.0;
}

void HeadingPriorCheck::predict(double v_mps, double omega_radps, double dt_s) {
  if (verdict_ != Verdict::kPending) {
    return;
  }
  const model::Pose2 moved = model::integrate_exact({dr_x_, dr_y_, dr_theta_}, {v_mps, omega_radps}, dt_s);
  dr_x_ = moved.x;
  dr_y_ = moved.y;
  dr_theta_ = moved.theta;
}

HeadingPriorCheck::Verdict HeadingPriorCheck::add_fix(double x_m, double y_m, double fix_std_m) {
  if (verdict_ != Verdict::kPending) {
    return verdict_;
  }
  if (fixes_ < kEndFixes) {
    first_fx_ += x_m;
    first_fy_ += y_m;
    first_dx_ += dr_x_;
    first_dy_ += dr_y_;
  }
  last_[fixes_ % kEndFixes] = {x_m, y_m, dr_x_, dr_y_};
  ++fixes_;
  if (fixes_ < 2 * kEndFixes) {
    return verdict_;  // the two ends must not share fixes
  }
  double fx = 0.0, fy = 0.0, dx = 0.0, dy = 0.0;
  for (const auto& fix : last_) {
    fx += fix[0];
    fy += fix[1];
    dx += fix[2];
    dy += fix[3];
  }
  const double n = static_cast<double>(kEndFixes);
  const double fix_dx = (fx - first_fx_) / n;
  const double fix_dy = (fy - first_fy_) / n;
  const double dr_dx = (dx - first_dx_) / n;
  const double dr_dy = (dy - first_dy_) / n;
  // The difference of two means of n fixes has std fix_std sqrt(2 / n) per axis.
  const double difference_std_m = fix_std_m * std::sqrt(2.0 / n);
  const double needed_m = 3.0 * difference_std_m / std::sin(tolerance_rad_);
  if (std::hypot(fix_dx, fix_dy) < needed_m || std::hypot(dr_dx, dr_dy) < needed_m) {
    return verdict_;
  }
  angle_error_rad_ = std::abs(wrap_angle(std::atan2(fix_dy, fix_dx) - std::atan2(dr_dy, dr_dx)));
  verdict_ = angle_error_rad_ <= tolerance_rad_ ? Verdict::kConfirmed : Verdict::kContradicted;
  return verdict_;
}

}  // namespace robodds::pf_estimator
