#include "components/pf_estimator/heading_track_check.hpp"

#include <algorithm>
#include <cmath>

#include "common/angle.hpp"
#include "common/model/diff_drive_kinematics.hpp"

namespace robodds::pf_estimator {

HeadingTrackCheck::HeadingTrackCheck(std::size_t window_fixes, double sigmas, double max_std_rad,
                                     double max_difference_rad)
    : capacity_(window_fixes), sigmas_(sigmas), max_std_rad_(max_std_rad), max_difference_rad_(max_difference_rad) {
  samples_.resize(capacity_);
}

void HeadingTrackCheck::reset() {
  count_ = 0;
  dr_x_ = dr_y_ = dr_theta_ = 0.0;
  track_theta_rad_ = track_theta_std_rad_ = difference_rad_ = 0.0;
}

void HeadingTrackCheck::predict(double v_mps, double omega_radps, double dt_s) {
  if (!enabled()) {
    return;
  }
  const model::Pose2 moved = model::integrate_exact({dr_x_, dr_y_, dr_theta_}, {v_mps, omega_radps}, dt_s);
  dr_x_ = moved.x;
  dr_y_ = moved.y;
  dr_theta_ = moved.theta;
}

void HeadingTrackCheck::add_fix(double x_m, double y_m) {
  if (!enabled()) {
    return;
  }
  samples_[count_ % capacity_] = {x_m, y_m, dr_x_, dr_y_};
  ++count_;
}

HeadingTrackCheck::Verdict HeadingTrackCheck::check(double cloud_theta_rad, double cloud_theta_var_rad2) {
  if (!enabled()) {
    return Verdict::kConsistent;
  }
  const std::size_t n = std::min(count_, capacity_);
  if (n < kMinFixes) {
    return Verdict::kPending;
  }
  double fx = 0.0, fy = 0.0, dx = 0.0, dy = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    fx += samples_[i].fix_x;
    fy += samples_[i].fix_y;
    dx += samples_[i].dr_x;
    dy += samples_[i].dr_y;
  }
  const double count = static_cast<double>(n);
  fx /= count;
  fy /= count;
  dx /= count;
  dy /= count;
  // Rotation phi minimising sum |f_k - R(phi) d_k|^2 of the centred sets: atan2(sum d x f, sum d . f).
  double dot = 0.0, cross = 0.0, spread = 0.0, fix_spread = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double ax = samples_[i].dr_x - dx, ay = samples_[i].dr_y - dy;
    const double bx = samples_[i].fix_x - fx, by = samples_[i].fix_y - fy;
    dot += ax * bx + ay * by;
    cross += ax * by - ay * bx;
    spread += ax * ax + ay * ay;
    fix_spread += bx * bx + by * by;
  }
  if (!(spread > 0.0)) {
    return Verdict::kPending;
  }
  const double phi = std::atan2(cross, dot);
  // Residual sum at the fit: sum |b|^2 + sum |a|^2 - 2 (dot cos phi + cross sin phi) = ... - 2 hypot.
  const double residual = std::max(0.0, fix_spread + spread - 2.0 * std::hypot(dot, cross));
  const double noise_var = residual / std::max(1.0, 2.0 * count - 3.0);  // per axis; 3 fitted: phi, shift
  const double phi_var = noise_var / spread;
  track_theta_rad_ = wrap_angle(phi + dr_theta_);
  track_theta_std_rad_ = std::sqrt(phi_var);
  difference_rad_ = wrap_angle(cloud_theta_rad - track_theta_rad_);
  if (track_theta_std_rad_ > max_std_rad_) {
    return Verdict::kPending;
  }
  double bound = sigmas_ * std::sqrt(phi_var + std::max(0.0, cloud_theta_var_rad2));
  if (max_difference_rad_ > 0.0) {
    bound = std::min(bound, max_difference_rad_);
  }
  return std::abs(difference_rad_) <= bound ? Verdict::kConsistent : Verdict::kContradicted;
}

}  // namespace robodds::pf_estimator
