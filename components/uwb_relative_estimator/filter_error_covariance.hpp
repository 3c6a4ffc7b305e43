#pragma once
// Issue 27: the covariance of the particle filters' (eq. 3-6 and [22]) error when their
// measurements' errors last longer than an epoch. Both filters weigh every epoch's measurement
// as if its error were new (the window's pose with lambda_d, or the 16 ranges with range_std_m);
// the UWB errors behind it are not: the pair's common mode lasts ~10 s, each link's bias ~2 s.
// Their particles then agree to a few cm while the estimate is off by tenths of a metre (the
// spread was 71-96 % over-confident: docs/results/paper3.md). This class does not change the
// filter: it follows the error of the filter's update as the filter applies it (a linear filter
// with the filter's own gain K) under the correlated error model, the "consider" covariance of a
// Schmidt-Kalman filter:
//   measurement error   e_t = B_t u_t + a_t c_t (RangeErrorMap: u the K L independent range errors,
//                       std s_i each, c the common one, std s_c), u and c first-order Gauss-Markov
//                       with time constants range_link_time_s and range_common_time_s;
//   prediction          eps' = F eps + odometry noise (F: relative_motion_jacobian),
//                       Cov(eps', c') = rho_c F Cov(eps, c), Cov(eps', u') = rho_u F Cov(eps, u);
//   update              eps+ = (I - K) eps + K e, with the cross-covariances of eps and (u, c);
//   start               the filter's cloud centred on a measurement: eps = e.
// The state is Sigma = Cov(eps) (3 x 3), Cov(eps, c) (3) and Cov(eps, u) (3 x K L). When every
// error is white (rho = 0) it is the ordinary Kalman covariance of that gain; when the errors
// never change (rho = 1) averaging gains nothing and Sigma stays the measurement's covariance.
// The window's pose is modelled as a fix with the errors of that epoch: the window smooths them
// over 3 s, a filter whose frequency response never exceeds 1, so the true error of the filter
// fed by it is no larger (conservative).
// Pure: Eigen + std; m, rad, s.
#include <cstddef>
#include <deque>
#include <optional>

#include <Eigen/Core>

#include "common/model/pose2.hpp"
#include "components/uwb_relative_estimator/relative_pose_covariance.hpp"

namespace robodds::uwb_relative_estimator {

/// K = P (P + R)^-1: the gain of a linear update with prior covariance P and measurement
/// covariance R (what a particle filter's Gaussian weights do to a Gaussian cloud). Zero when
/// P + R is not positive definite.
Eigen::Matrix3d update_gain(const Eigen::Matrix3d& prior, const Eigen::Matrix3d& measurement_covariance);

/// The positive semi-definite part of symmetric `m` (only its lower triangle is read; its
/// eigen-directions with positive eigenvalues;
/// covariance matching: the smallest addition that makes a covariance hold a seen discrepancy).
/// Zero when the eigen-decomposition fails.
Eigen::Matrix3d positive_part(const Eigen::Matrix3d& m);

class FilterErrorCovariance {
 public:
  /// `params`: range_common_time_s and range_link_time_s (validated; std::invalid_argument).
  explicit FilterErrorCovariance(const UncertaintyParams& params);

  /// False until start().
  bool started() const { return started_; }

  /// The filter (re)started around a measurement whose error is `error`: eps = e.
  void start(const RangeErrorMap& error);
  /// The filter (re)started around a measurement of known covariance whose error maps to no range
  /// (e.g. a degenerate geometry): Sigma = covariance, uncorrelated with the range errors.
  void start(const Eigen::Matrix3d& covariance);

  /// One epoch of dead reckoning over `dt_s` (>= 0) from the estimate `x` with both robots'
  /// increments (std xy_std_m on x and y, theta_std_rad on theta, each robot). Ignored before start().
  void predict(const model::Pose2& x, const model::Pose2& own_increment, const model::Pose2& other_increment,
               double dt_s, double xy_std_m, double theta_std_rad);

  /// An update with gain `gain` on a measurement whose error is `error`. Ignored before start().
  /// A map with another number of ranges than the one before restarts the cross-covariance with
  /// the independent errors at zero.
  void update(const Eigen::Matrix3d& gain, const RangeErrorMap& error);

  /// Sigma, the covariance of the filter's error (m^2, m rad, rad^2); zero before start().
  const Eigen::Matrix3d& covariance() const { return covariance_; }

 private:
  UncertaintyParams params_;
  bool started_ = false;
  Eigen::Matrix3d covariance_ = Eigen::Matrix3d::Zero();
  Eigen::Vector3d common_cross_ = Eigen::Vector3d::Zero();          // Cov(eps, c)
  Eigen::Matrix<double, 3, Eigen::Dynamic> independent_cross_;      // Cov(eps, u)
  Eigen::Matrix<double, 3, Eigen::Dynamic> node_cross_;             // Cov(eps, b), the node biases
};

/// The filters' own consistency check against the eq. (1) fixes (issue 27: valid and uncertain
/// "as the estimator's own check says"). The covariance above is honest only as long as the
/// filter follows its measurements; a filter that lost them (a cloud that converged on a wrong
/// pose and is kept there by its own odometry and by ranges it explains away, e.g. the baseline
/// [22] with 0.25 m arrays and non-line-of-sight ranges: 8-10 m off for a minute while the fixes
/// were within 1-2 m) is told so by the fixes. Per fix: the innovation delta = fix - estimate
/// (heading wrapped) and the fix's covariance. Over the last innovation_window_epochs fixes: the
/// component-wise median of delta (robust to a wrong fix) and the typical fix's covariance S (the
/// fix of median trace: an outlier fix's own huge variance must not explain the discrepancy away);
/// excess() is the part of median_delta median_delta^T that S does not explain (its positive
/// eigen-directions: covariance matching), i.e. how far the fixes alone place the peer from the
/// estimate beyond their own uncertainty. The filter's own covariance does not excuse it: it
/// assumes the filter follows the fixes. A filter that follows them adds nothing or little (the
/// median over 5 s of fix errors that last 2-10 s is not smaller than one fix's). lost() says
/// when the filter should rather be restarted (the estimator does: relative_estimator.cpp).
class InnovationMonitor {
 public:
  /// `params`: innovation_window_epochs, lost_filter_d2, lost_mean_d2, lost_window_epochs (validated).
  explicit InnovationMonitor(const UncertaintyParams& params);
  /// Forgets every fix (the filter restarted).
  void reset();
  /// One fix against the filter's estimate; non-finite input is ignored. `own_error_covariance`:
  /// the part of the fix's covariance that the filter does not share (the independent range
  /// errors': the common mode and the node biases reach the filter through the same ranges and
  /// cancel in fix - estimate); lost() tests against it. Without it, the whole fix covariance.
  void add(const model::Pose2& estimate, const model::Pose2& fix, const Eigen::Matrix3d& fix_covariance,
           const std::optional<Eigen::Matrix3d>& own_error_covariance = std::nullopt);
  /// The unexplained discrepancy (above), positive semi-definite; zero with fewer fixes than a
  /// fifth of the window (and 3). `estimate_covariance`: what the estimate's own covariance
  /// explains too (an estimate independent of the fixes: the odometry stage's dead reckoning);
  /// zero for the filters, which assume they follow the fixes.
  Eigen::Matrix3d excess(const Eigen::Matrix3d& estimate_covariance = Eigen::Matrix3d::Zero()) const;
  /// As excess(), for an estimate whose error grows with time (a dead reckoning: a wheel slip
  /// drifts as t): the window's median innovation sits half a window behind such a drift, so it
  /// is carried to the newest fix along the window's trend, median + (median of the newer half -
  /// median of the older half), each component (the odometry stage: seed 9 of experiment 2 with
  /// 0.25 m arrays and NLOS was over-confident for 2.01 s in a row while its error grew 0.2 m/s).
  Eigen::Matrix3d drifting_excess(const Eigen::Matrix3d& estimate_covariance) const;
  /// The lost-filter test, once per epoch: with enough fixes (as excess()), the median innovation
  /// m and the typical fix's own-error covariance S (add(); the fix of median trace: an outlier's
  /// own variance must not hide the discrepancy) give d^2 = m^T (S + filter_covariance)^-1 m; true when d^2 exceeds
  /// lost_filter_d2, or its mean over the last lost_window_epochs tests (at least half of them)
  /// exceeds lost_mean_d2 (the fixes place the peer where the filter says it cannot be, at once
  /// or for long). Then `correction` is m (add it to the estimate, heading wrapped) and
  /// `fix_covariance` S; the caller restarts the filter and reset()s this.
  bool lost(const Eigen::Matrix3d& filter_covariance, Eigen::Vector3d& correction, Eigen::Matrix3d& fix_covariance);

 private:
  /// The component-wise median innovation and the typical fix's covariance (the fix of median
  /// trace); false with too few fixes.
  bool typical(Eigen::Vector3d& median_innovation, Eigen::Matrix3d& typical_covariance,
               const std::deque<Eigen::Matrix3d>& covariances) const;
  /// The component-wise median of innovations_[first, last).
  Eigen::Vector3d median_innovation(std::size_t first, std::size_t last) const;
  /// excess() (carry_trend false) and drifting_excess() (true): the positive part of m m^T - S -
  /// estimate_covariance, m the typical innovation (carried along the trend), S the typical fix's.
  Eigen::Matrix3d unexplained(const Eigen::Matrix3d& estimate_covariance, bool carry_trend) const;

  UncertaintyParams params_;
  std::deque<Eigen::Vector3d> innovations_;
  std::deque<Eigen::Matrix3d> covariances_;
  std::deque<Eigen::Matrix3d> own_covariances_;  // add()'s own_error_covariance
  std::deque<double> recent_d2_;  // lost()'s d^2 of the last lost_window_epochs tests
  double recent_d2_sum_ = 0.0;
};

}  // namespace robodds::uwb_relative_estimator
