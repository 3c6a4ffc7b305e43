#include "components/pf_estimator/consistency.hpp"

#include <cmath>

namespace robodds::pf_estimator {

double FixInnovation::normalized_square(double vx, double vy) const {
  // v^T S^-1 v with the closed-form inverse of the 2 x 2 S.
  const double determinant = sxx * syy - sxy * sxy;
  return (syy * vx * vx - 2.0 * sxy * vx * vy + sxx * vy * vy) / determinant;
}

FixInnovation position_fix_innovation(const ParticleSet& particles, const Eigen::ArrayXd& normalized_weights,
                                      double z_x_m, double z_y_m, double measurement_std_m) {
  const Eigen::ArrayXd& w = normalized_weights;
  const double mean_x = (w * particles.x).sum();
  const double mean_y = (w * particles.y).sum();
  // One loop, no temporaries: the filter does not allocate per update.
  double pxx = 0.0, pyy = 0.0, pxy = 0.0;
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    const double dx = particles.x[i] - mean_x;
    const double dy = particles.y[i] - mean_y;
    pxx += w[i] * dx * dx;
    pyy += w[i] * dy * dy;
    pxy += w[i] * dx * dy;
  }
  const double variance = measurement_std_m * measurement_std_m;
  FixInnovation innovation;
  innovation.ex = z_x_m - mean_x;
  innovation.ey = z_y_m - mean_y;
  innovation.sxx = pxx + variance;
  innovation.syy = pyy + variance;
  innovation.sxy = pxy;
  return innovation;
}

double position_fix_nis(const ParticleSet& particles, const Eigen::ArrayXd& normalized_weights,
                        double z_x_m, double z_y_m, double measurement_std_m) {
  return position_fix_innovation(particles, normalized_weights, z_x_m, z_y_m, measurement_std_m).nis();
}

double chi_square_2dof_quantile(double probability) { return -2.0 * std::log1p(-probability); }

InconsistencyMonitor::InconsistencyMonitor(double window_fixes, double max_rejected_share,
                                           double max_mean_nis, double bias_window_fixes,
                                           double max_bias_nis)
    : gain_(1.0 / window_fixes),
      max_rejected_share_(max_rejected_share),
      max_mean_nis_(max_mean_nis),
      bias_gain_(1.0 / bias_window_fixes),
      max_bias_nis_(max_bias_nis) {}

bool InconsistencyMonitor::add(double nis, bool rejected) {
  rejected_share_ += gain_ * ((rejected ? 1.0 : 0.0) - rejected_share_);
  if (!rejected) {
    mean_nis_ += gain_ * (nis - mean_nis_);
  }
  return rejected_share_ > max_rejected_share_ || (max_mean_nis_ > 0.0 && mean_nis_ > max_mean_nis_);
}

bool InconsistencyMonitor::add(const FixInnovation& innovation, bool rejected) {
  if (!rejected) {
    mean_ex_ += bias_gain_ * (innovation.ex - mean_ex_);
    mean_ey_ += bias_gain_ * (innovation.ey - mean_ey_);
    // An EMA of white innovations has covariance S g / (2 - g): normalise by it.
    bias_nis_ = innovation.normalized_square(mean_ex_, mean_ey_) * (2.0 - bias_gain_) / bias_gain_;
  }
  const bool lost = add(innovation.nis(), rejected);
  return lost || (max_bias_nis_ > 0.0 && bias_nis_ > max_bias_nis_);
}

void InconsistencyMonitor::reset() {
  rejected_share_ = 0.0;
  mean_nis_ = kConsistentMeanNis;
  mean_ex_ = 0.0;
  mean_ey_ = 0.0;
  bias_nis_ = 0.0;
}

}  // namespace robodds::pf_estimator
