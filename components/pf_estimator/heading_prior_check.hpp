#pragma once
// Confirms a heading given as known (PfParams::init_theta_known) by the fixes' displacement
// (issue 27, finding 3). A prior heading makes every particle agree, so the cloud's heading spread
// says "certain" from t = 0 whether the prior is right or 120 deg wrong; only the fixes can tell.
//
// From the (re)initialisation on, the prior heading is dead-reckoned with the measured odometry
// (the filter's mean motion, no noise). The mean of the first kEndFixes accepted fixes and the
// mean of the last kEndFixes are compared with the dead-reckoned positions at the same fixes:
// with a right prior both displacements point the same way. The verdict waits until the fixes'
// displacement is long enough to measure its direction (3 sigma of the difference of the two
// means, sigma = the fix std / sqrt(kEndFixes / 2), within the tolerance: |D| >= 3 sigma /
// sin(tolerance)); then the prior is confirmed if the angle between the two displacements is
// within the tolerance, contradicted otherwise.

#include <array>
#include <cstddef>

namespace robodds::pf_estimator {

class HeadingPriorCheck {
 public:
  enum class Verdict {
    kNotNeeded,     // no prior to check (heading learned from motion, or checking off)
    kPending,       // not moved far enough yet
    kConfirmed,     // the fixes moved the way the prior says
    kContradicted,  // they did not: the prior is wrong
  };
  static constexpr std::size_t kEndFixes = 10;

  /// tolerance_rad in (0, pi/2) (0 = never check: every prior counts as confirmed).
  explicit HeadingPriorCheck(double tolerance_rad) : tolerance_rad_(tolerance_rad) {}

  /// Starts a check of the heading prior_theta_rad (rad, world frame) at a (re)initialisation.
  void start(double prior_theta_rad);
  /// No prior to check (e.g. after a recovery, whose headings are partly uniform).
  void stop() { verdict_ = Verdict::kNotNeeded; }
  /// The measured odometry (m/s, rad/s, s) moves the dead-reckoned pose.
  void predict(double v_mps, double omega_radps, double dt_s);
  /// An accepted fix (m, world frame) and the fix std per axis (m) now believed; returns the verdict.
  Verdict add_fix(double x_m, double y_m, double fix_std_m);

  Verdict verdict() const { return verdict_; }
  /// Angle between the fixes' and the dead-reckoned displacement at the verdict (rad, >= 0).
  double angle_error_rad() const { return angle_error_rad_; }

 private:
  double tolerance_rad_;
  Verdict verdict_ = Verdict::kNotNeeded;
  double dr_x_ = 0.0, dr_y_ = 0.0, dr_theta_ = 0.0;  // dead-reckoned pose since start (m, rad)
  std::size_t fixes_ = 0;
  // Sums over the first kEndFixes fixes: fix and dead-reckoned positions (m).
  double first_fx_ = 0.0, first_fy_ = 0.0, first_dx_ = 0.0, first_dy_ = 0.0;
  // The last kEndFixes fixes (ring buffer): fix x, y and dead-reckoned x, y (m).
  std::array<std::array<double, 4>, kEndFixes> last_{};
  double angle_error_rad_ = 0.0;
};

}  // namespace robodds::pf_estimator
