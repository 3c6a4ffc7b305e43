#pragma once
// Issue 27: the uwb stage's (eq. 1) own consistency check over time. One epoch's residuals cannot
// show an error that moves the fit as the pose would move (a range bias shared by the links of one
// node, a board that delays the links through it): the fit absorbs it into heading and bearing.
// Its configured part (node_bias_std_m) covers what was seen; an error larger or of another shape
// (a stronger obstacle, another geometry) would leave the stage over-confident. What one epoch
// cannot show, the sequence of fixes can, as far as the error changes: odometry carries an earlier
// fix to now with a small, known error, and the difference between this fix and that dead-reckoned
// one contains the change of the fixes' error over the lag.
//
// Per valid fix at time t: the fix kept from about fix_check_lag_s before (fixes are kept every
// twentieth of the lag; the reference is 1-1.05 lags old), dead-reckoned by both
// robots' odometry to t (x' = inverse(m_i) x m_j each epoch, Jacobian F and odometry covariance Q
// accumulated), gives the innovation nu = fix_t - x'_old (heading wrapped). Under the error model
// the stages report with (RangeErrorMap: independent range errors u, common c, node biases b, each
// Gauss-Markov with range_link_time_s / range_common_time_s), its covariance is
//   S = P_t + F P_old F^T + Q - C - C^T,
//   C = [rho_u B_t D B_old^T + rho_c s_c^2 a_t a_old^T + rho_c s_n^2 N_t N_old^T] F^T,
// rho = exp(-lag / tau), D the geometric mean of both fixes' per-range variances. The test
// statistics are the position's d^2 = nu_xy^T S_xy^-1 nu_xy (mean 2 when the model holds) and the
// heading's z^2 = nu_theta^2 / S_theta (mean 1); over the last fix_check_window_epochs tests their
// means give the factors by which the model underrates the fixes' errors (covariance matching):
// position_scale() = max(1, mean d^2 / 2), heading_scale() = max(1, mean z^2); and a fix whose own
// test fails (d^2 or z^2 beyond chi-square's 99 % quantile: a fit that jumped to a wrong bearing
// and heading for an epoch, which a window's mean takes in only afterwards) is scaled by its own
// d^2 / 2 or z^2 when that is larger. The stage reports its covariance scaled by them
// (inflate()). A model that holds or overrates the errors scales little (1 % of the fixes by their
// gate); a bias that never changes stays invisible (nothing but the truth would show it).
// Pure: Eigen + std; m, rad, s.
#include <cstddef>
#include <deque>

#include <Eigen/Core>

#include "common/model/pose2.hpp"
#include "components/uwb_relative_estimator/relative_pose_covariance.hpp"

namespace robodds::uwb_relative_estimator {

class FixTrackCheck {
 public:
  /// `params`: fix_check_lag_s (0: the check is off, inflate() returns its input),
  /// fix_check_window_epochs, range_link_time_s, range_common_time_s (validated).
  explicit FixTrackCheck(const UncertaintyParams& params);

  /// Forgets every fix and test.
  void reset();
  /// One epoch of both robots' motion (increments in their own frames at the previous epoch; std
  /// xy_std_m on x and y, theta_std_rad on theta, each robot): every kept fix is dead-reckoned to now.
  void predict(const model::Pose2& own_increment, const model::Pose2& other_increment, double xy_std_m,
               double theta_std_rad);
  /// A valid fix at `time_s` (non-decreasing) with its error map and reported covariance: tested
  /// against the kept fix of about fix_check_lag_s ago (when one is between 1 and 2 lags old), then
  /// kept. Non-finite input is ignored.
  void add(double time_s, const model::Pose2& fix, const RangeErrorMap& error, const Eigen::Matrix3d& covariance);

  /// >= 1: the mean position d^2 of the recent tests over its expectation 2, or the latest add()'s
  /// d^2 / 2 when that fix failed its test (d^2 > 9.21) and it is larger (1 without tests).
  double position_scale() const;
  /// >= 1: the mean heading z^2 of the recent tests, or the latest add()'s z^2 when that fix
  /// failed its test (z^2 > 6.63) and it is larger (1 without tests).
  double heading_scale() const;
  /// `covariance` with its position rows and columns scaled by sqrt(position_scale()) and its
  /// heading row and column by sqrt(heading_scale()) (positive definite stays so).
  Eigen::Matrix3d inflate(const Eigen::Matrix3d& covariance) const;
  /// Tests made since construction or reset() (for tests and counts).
  std::size_t tests() const { return tests_; }

 private:
  struct Kept {
    double time_s = 0.0;
    model::Pose2 pose;                                        // dead-reckoned to the latest epoch
    Eigen::Matrix3d propagation = Eigen::Matrix3d::Identity();  // F: d pose_now / d pose_then
    Eigen::Matrix3d odometry = Eigen::Matrix3d::Zero();         // Q: the dead reckoning's covariance
    RangeErrorMap error;
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  };

  void test(double time_s, const model::Pose2& fix, const RangeErrorMap& error, const Eigen::Matrix3d& covariance,
            const Kept& old);

  UncertaintyParams params_;
  std::deque<Kept> kept_;
  std::deque<Eigen::Vector2d> recent_;  // (d^2, z^2) of the last fix_check_window_epochs tests
  Eigen::Vector2d recent_sum_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d last_ = Eigen::Vector2d::Zero();  // the latest add()'s test (zero: none)
  std::size_t tests_ = 0;
};

}  // namespace robodds::uwb_relative_estimator
