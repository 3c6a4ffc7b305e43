#include "components/pf_estimator/pose_estimate.hpp"

#include <algorithm>
#include <cmath>

#include "common/angle.hpp"
#include "common/model/diff_drive_kinematics.hpp"

namespace robodds::pf_estimator {

PoseEstimate weighted_pose_estimate(const ParticleSet& particles,
                                    const Eigen::ArrayXd& normalized_weights) {
  const Eigen::ArrayXd& w = normalized_weights;
  PoseEstimate estimate;
  const double mean_x = (w * particles.x).sum();
  const double mean_y = (w * particles.y).sum();
  // One loop with sin and cos of the same angle: the compiler fuses them into one sincos call.
  double sum_sin = 0.0;
  double sum_cos = 0.0;
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    sum_sin += w[i] * std::sin(particles.theta[i]);
    sum_cos += w[i] * std::cos(particles.theta[i]);
  }
  const double mean_theta = std::atan2(sum_sin, sum_cos);
  estimate.mean << mean_x, mean_y, mean_theta;

  double xx = 0.0, xy = 0.0, xt = 0.0, yy = 0.0, yt = 0.0, tt = 0.0;
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    const double dx = particles.x[i] - mean_x;
    const double dy = particles.y[i] - mean_y;
    const double dt = wrap_angle(particles.theta[i] - mean_theta);
    xx += w[i] * dx * dx;
    xy += w[i] * dx * dy;
    xt += w[i] * dx * dt;
    yy += w[i] * dy * dy;
    yt += w[i] * dy * dt;
    tt += w[i] * dt * dt;
  }
  estimate.covariance << xx, xy, xt,  //
      xy, yy, yt,                     //
      xt, yt, tt;
  return estimate;
}

bool is_valid(const PoseEstimate& estimate, double max_position_std_m, double max_heading_std_rad) {
  const Eigen::Matrix3d& c = estimate.covariance;
  const bool position_ok = std::sqrt(c(0, 0) + c(1, 1)) < max_position_std_m;
  const bool heading_ok = max_heading_std_rad <= 0.0 || std::sqrt(c(2, 2)) < max_heading_std_rad;
  return position_ok && heading_ok;
}

bool next_validity(const PoseEstimate& estimate, const ValidityLimits& limits, bool was_valid) {
  const bool check_heading = limits.enter_max_heading_std_rad > 0.0;
  const double heading_limit = !check_heading ? 0.0
                               : was_valid    ? limits.keep_max_heading_std_rad
                                              : limits.enter_max_heading_std_rad;
  return is_valid(estimate, limits.max_position_std_m, heading_limit);
}

bool ValidityTracker::next(const PoseEstimate& estimate, bool confirmed, std::size_t restarts) {
  if (restarts != restarts_) {
    established_ = false;
    restarts_ = restarts;
  }
  const bool valid = confirmed && next_validity(estimate, limits_, established_);
  established_ = established_ || valid;
  return valid;
}

PoseEstimate extrapolate_estimate(const PoseEstimate& estimate, double v_mps, double omega_radps,
                                  double omega_var_radps2, double age_s) {
  if (!(age_s > 0.0)) {
    return estimate;
  }
  PoseEstimate moved = estimate;
  const model::Pose2 pose =
      model::integrate_exact({estimate.mean.x(), estimate.mean.y(), estimate.mean.z()}, {v_mps, omega_radps}, age_s);
  moved.mean << pose.x, pose.y, pose.theta;
  moved.covariance(2, 2) += std::max(0.0, omega_var_radps2) * age_s * age_s;
  return moved;
}

}  // namespace robodds::pf_estimator
