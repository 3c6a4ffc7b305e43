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

namespace robodds::pf_estimator {

/// The innovation e of a fix and its covariance S (m, m^2).
struct FixInnovation {
  double ex = 0.0;
  double ey = 0.0;
  double sxx = 1.0;
  double syy = 1.0;
  double sxy = 0.0;
  /// v^T S^-1 v for any vector v (e.g. a mean of innovations).
  double normalized_square(double vx, double vy) const;
  /// d^2 = e^T S^-1 e.
  double nis() const { return normalized_square(ex, ey); }
};

/// Innovation of the fix (z_x_m, z_y_m) (world frame, m) against the cloud with normalised
/// weights. measurement_std_m > 0, so S is positive definite whatever the cloud.
FixInnovation position_fix_innovation(const ParticleSet& particles, const Eigen::ArrayXd& normalized_weights,
                                      double z_x_m, double z_y_m, double measurement_std_m);

/// d^2 of that fix.
double position_fix_nis(const ParticleSet& particles, const Eigen::ArrayXd& normalized_weights,
                        double z_x_m, double z_y_m, double measurement_std_m);

/// The chi-square quantile with 2 degrees of freedom, -2 ln(1 - probability): 9.21 for 0.99.
/// probability in [0, 1).
double chi_square_2dof_quantile(double probability);

/// Notices a lost filter from exponential moving averages over the last fixes (weight
/// 1 / window each):
/// - the share of rejected fixes over `window_fixes` (a jump: every fix is far off);
/// - the mean d^2 of the accepted fixes over `window_fixes` (a drift inside the gate; 2 if
///   consistent);
/// - the mean innovation vector m of the accepted fixes over `bias_window_fixes`, as
///   b^2 = m^T S^-1 m (2 - g) / g with g = 1 / bias_window_fixes: chi-square(2) for white
///   innovations, large when the fixes sit on one side of the estimate for seconds (a wrong
///   heading while the robot barely moves: d^2 stays small, the side does not change).
/// Outliers only raise the share, by 1 / window_fixes each, so rare ones never make the filter
/// look lost, and they never enter the averages of the accepted fixes. A threshold <= 0 turns
/// its criterion off.
class InconsistencyMonitor {
 public:
  InconsistencyMonitor(double window_fixes, double max_rejected_share, double max_mean_nis,
                       double bias_window_fixes = 1.0, double max_bias_nis = 0.0);
  /// Adds one fix (its d^2 and whether the gate rejected it); true if the filter now looks lost.
  bool add(double nis, bool rejected);
  /// The same, with the innovation itself (feeds the bias criterion too).
  bool add(const FixInnovation& innovation, bool rejected);
  double rejected_share() const { return rejected_share_; }
  double mean_nis() const { return mean_nis_; }
  double bias_nis() const { return bias_nis_; }
  void reset();

  static constexpr double kConsistentMeanNis = 2.0;

 private:
  double gain_;
  double max_rejected_share_;
  double max_mean_nis_;
  double bias_gain_;
  double max_bias_nis_;
  double rejected_share_ = 0.0;
  double mean_nis_ = kConsistentMeanNis;
  double mean_ex_ = 0.0;
  double mean_ey_ = 0.0;
  double bias_nis_ = 0.0;
};

}  // namespace robodds::pf_estimator
