#pragma once
// Checks a heading the cloud learned against the track of the fixes (issue 27, finding 2): with
// fixes noisier than configured, the cloud can settle early on a wrong heading (92-121 deg off, or
// 30-50 deg at a reported 7-12 deg) with a spread small enough to be called valid.
//
// From the (re)initialisation on, the measured odometry is dead-reckoned in a frame of its own
// (origin and heading 0 at the start). Each accepted fix is stored with the dead-reckoned position
// at its time (the last window_fixes). The fixes are the dead-reckoned track rotated by the heading
// phi the robot had at the start, shifted, plus noise: phi is fitted in closed form (2-D
// Procrustes, rotation only, of the centred point sets), its std from the fit's own residuals
// (the fix noise as seen, not as configured): sigma_phi^2 = s^2 / sum |d_k - d_mean|^2. The cloud's
// heading theta now implies phi_cloud = theta - (dead-reckoned heading now). The verdict:
//   kPending: fewer than kMinFixes fixes, or sigma_phi above max_std_rad (the track does not know
//             the heading as well as the cloud must to be valid: not moved far enough);
//   kConsistent: |phi_cloud - phi| <= sigmas x sqrt(sigma_phi^2 + var theta) and, if
//                max_difference_rad > 0, <= max_difference_rad (the combined sigmas of a track and a
//                cloud both near the valid limit allow ~50 deg: a cloud 38 deg off passed);
//   kContradicted: beyond.
// Assumes the odometry is right up to small errors over the window (a wheel scale error bends the
// dead reckoning by slip / track per metre: 2 % on 0.3 m, 0.067 rad per m of creep).
//
// While driving (check_drifting(), after the cloud passed once): the track over the last
// window_fixes fixes is dead-reckoned again from the odometry increments stored with each fix, and
// the fit finds the turn slip k of that odometry as well (theta' = omega - k v), independently of the
// cloud: a cloud that learned a wrong turn slip bends its heading (issue 27, fixes 2x noisier: 11-16
// deg off at a reported 2-3 deg for 50 s), and a dead reckoning bent with the cloud's slip (or with
// none, on a robot whose wheel reads fast) bends alike. Rotation phi by Procrustes for each k, k by
// Gauss-Newton steps; the covariance of (phi, k) from the residuals. The track's heading now is
// phi + the dead-reckoned heading change since the window's first fix with k removed; its variance
// from that covariance plus the odometry's turn-rate noise accumulated since the window's fixes
// (on average; predict()'s omega_var).

#include <cstddef>
#include <vector>

namespace robodds::pf_estimator {

class HeadingTrackCheck {
 public:
  enum class Verdict { kPending, kConsistent, kContradicted };
  static constexpr std::size_t kMinFixes = 20;

  /// window_fixes >= kMinFixes (0 = off: every verdict kConsistent); sigmas > 0; max_std_rad > 0;
  /// max_difference_rad >= 0 (0 = no cap).
  HeadingTrackCheck(std::size_t window_fixes, double sigmas, double max_std_rad, double max_difference_rad = 0.0);

  bool enabled() const { return capacity_ > 0; }
  /// Forgets every fix and restarts the dead reckoning (a (re)initialisation).
  void reset();
  /// The measured odometry (m/s, rad/s, s) moves the dead-reckoned pose. omega_var_radps2: the
  /// variance of this omega sample ((rad/s)^2), accumulated as the dead-reckoned heading's drift.
  void predict(double v_mps, double omega_radps, double dt_s, double omega_var_radps2 = 0.0);
  /// An accepted fix (m, world frame).
  void add_fix(double x_m, double y_m);
  /// The verdict on the cloud's heading now (rad, world) and its variance (rad^2).
  Verdict check(double cloud_theta_rad, double cloud_theta_var_rad2);
  /// As check(), with the odometry's turn slip fitted too and the drift since the window's fixes
  /// counted (see above).
  Verdict check_drifting(double cloud_theta_rad, double cloud_theta_var_rad2);
  /// From the last check_drifting() that judged: the odometry's turn slip the track fitted (rad/m)
  /// and its std (rad/m).
  double slip_radpm() const { return slip_radpm_; }
  double slip_std_radpm() const { return slip_std_radpm_; }

  /// From the last check() with enough fixes: the track's heading now (rad, world: the fitted phi
  /// plus the dead-reckoned heading), its std (rad) and the cloud's difference to it (rad, wrapped).
  double track_theta_rad() const { return track_theta_rad_; }
  double track_theta_std_rad() const { return track_theta_std_rad_; }
  double difference_rad() const { return difference_rad_; }
  std::size_t fixes() const { return count_; }
  /// The window holds every fix since reset(): the track knows all the fixes said since.
  bool holds_every_fix() const { return count_ <= capacity_; }
  /// The std of the odometry's turn slip (rad/m) the last check_drifting() fitted, given a prior
  /// N(0, prior_std_radpm^2) on it as well (the filter's: the fit itself takes the slip as free, so
  /// that it judges the cloud independently of the cloud's prior): 1 / sqrt(1 / var_fit + 1 / var_prior),
  /// the exact marginal of a linear Gaussian fit. prior_std_radpm <= 0: the fit's.
  double slip_std_with_prior_radpm(double prior_std_radpm) const;

 private:
  struct Sample {
    double fix_x, fix_y, dr_x, dr_y;
    // The odometry since the previous fix: signed distance (m), heading change (rad), its variance (rad^2).
    double ds, dtheta, dvar;
  };
  /// The verdict on a track heading (rad) with its variance (rad^2).
  Verdict verdict(double track_theta_rad, double track_var, double cloud_theta_rad, double cloud_theta_var_rad2);
  std::size_t capacity_;
  double sigmas_;
  double max_std_rad_;
  double max_difference_rad_;
  std::vector<Sample> samples_;  // ring buffer of the last capacity_ accepted fixes
  std::size_t count_ = 0;        // fixes added since reset()
  double dr_x_ = 0.0, dr_y_ = 0.0, dr_theta_ = 0.0;
  double pending_ds_ = 0.0, pending_dtheta_ = 0.0, pending_dvar_ = 0.0;  // since the last fix
  double slip_radpm_ = 0.0;
  double slip_std_radpm_ = 0.0;
  double track_theta_rad_ = 0.0;
  double track_theta_std_rad_ = 0.0;
  double difference_rad_ = 0.0;
};

}  // namespace robodds::pf_estimator
