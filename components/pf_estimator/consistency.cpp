#include "components/pf_estimator/consistency.hpp"

#include <cmath>

namespace robodds::pf {

double position_fix_nis(const ParticleSet& particles, const Eigen::ArrayXd& normalized_weights,
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
  const double sxx = pxx + variance;
  const double syy = pyy + variance;
  const double sxy = pxy;
  const double ex = z_x_m - mean_x;
  const double ey = z_y_m - mean_y;
  // e^T S^-1 e with the closed-form inverse of the 2 x 2 S.
  const double determinant = sxx * syy - sxy * sxy;
  return (syy * ex * ex - 2.0 * sxy * ex * ey + sxx * ey * ey) / determinant;
}

double chi_square_2dof_quantile(double probability) { return -2.0 * std::log1p(-probability); }

InconsistencyMonitor::InconsistencyMonitor(double window_fixes, double max_rejected_share,
                                           double max_mean_nis)
    : gain_(1.0 / window_fixes), max_rejected_share_(max_rejected_share), max_mean_nis_(max_mean_nis) {}

bool InconsistencyMonitor::add(double nis, bool rejected) {
  rejected_share_ += gain_ * ((rejected ? 1.0 : 0.0) - rejected_share_);
  if (!rejected) {
    mean_nis_ += gain_ * (nis - mean_nis_);
  }
  return rejected_share_ > max_rejected_share_ || mean_nis_ > max_mean_nis_;
}

void InconsistencyMonitor::reset() {
  rejected_share_ = 0.0;
  mean_nis_ = kConsistentMeanNis;
}

}  // namespace robodds::pf
