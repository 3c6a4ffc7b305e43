#pragma once
// Consistency of the position fixes with the particle cloud (issue 12): a chi-square gate on each
// fix and a monitor that notices when fixes keep disagreeing (the filter is lost: wrong start,
// kidnapped robot, unmodelled odometry error), so the filter can reject outliers and recover.
//
// The innovation of a fix z is e = z - m, m the weighted mean of the particles' (x, y); its
// covariance is S = P + s^2 I, P the weighted (x, y) covariance of the cloud and s the fix's
// standard deviation per axis. The normalised innovation squared d^2 = e^T S^-1 e of a consistent
// filter is chi-square distributed with 2 degrees of freedom (mean 2).

#include <Eigen/Core>

#include "components/pf_estimator/particle_set.hpp"

namespace robodds::pf {

/// d^2 of the fix (z_x_m, z_y_m) (world frame, m) against the cloud with normalised weights.
/// measurement_std_m > 0, so S is positive definite whatever the cloud.
double position_fix_nis(const ParticleSet& particles, const Eigen::ArrayXd& normalized_weights,
                        double z_x_m, double z_y_m, double measurement_std_m);

/// The chi-square quantile with 2 degrees of freedom, -2 ln(1 - probability): 9.21 for 0.99.
/// probability in [0, 1).
double chi_square_2dof_quantile(double probability);

/// Notices a lost filter from two exponential moving averages over about `window_fixes` fixes
/// (weight 1 / window_fixes each): the share of rejected fixes (a jump: every fix is far off) and
/// the mean d^2 of the accepted ones (a drift that stays inside the gate; consistent: 2).
/// Outliers only raise the share, by 1 / window_fixes each, so rare ones never make the filter
/// look lost, and they never enter the d^2 average.
class InconsistencyMonitor {
 public:
  InconsistencyMonitor(double window_fixes, double max_rejected_share, double max_mean_nis);
  /// Adds one fix (its d^2 and whether the gate rejected it); true if the filter now looks lost.
  bool add(double nis, bool rejected);
  double rejected_share() const { return rejected_share_; }
  double mean_nis() const { return mean_nis_; }
  void reset();

  static constexpr double kConsistentMeanNis = 2.0;

 private:
  double gain_;
  double max_rejected_share_;
  double max_mean_nis_;
  double rejected_share_ = 0.0;
  double mean_nis_ = kConsistentMeanNis;
};

}  // namespace robodds::pf
