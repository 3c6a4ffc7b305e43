#pragma once
// Particle-filter pose estimator of paper 1, section 2 (eq. 4-7), extended from the paper's
// position state [p_x, p_y] to the pose [x, y, theta] so the motion model can be driven by
// odometry and the heading is learned from the fixes while the robot moves.
//
// Robustness (issue 12): every particle also carries a turn slip k (rad/m, see PfParams), the
// turn-rate noise grows with the wheels' motion (none at standstill), each fix is checked against
// the cloud (chi-square gate, consistency.hpp) and rejected as an outlier if it fails, and when
// fixes keep disagreeing the cloud is redrawn around the latest fixes (recovery).
//
// Frames and units: world frame, x/y in m, theta in rad counter-clockwise from world +x,
// wrapped to (-pi, pi]. Speeds in m/s and rad/s, time steps in s.
//
// Cycle: predict() for every odometry sample, update() for every position fix, estimate() when
// an output is wanted. Not thread-safe; one instance per robot. All randomness comes from one
// RandomEngine seeded in the constructor, so the same seed and inputs give bit-identical output.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/random.hpp"
#include "components/pf_estimator/consistency.hpp"
#include "components/pf_estimator/fix_noise_estimator.hpp"
#include "components/pf_estimator/heading_prior_check.hpp"
#include "components/pf_estimator/heading_track_check.hpp"
#include "components/pf_estimator/particle_set.hpp"
#include "components/pf_estimator/pf_params.hpp"
#include "components/pf_estimator/pose_estimate.hpp"

namespace robodds::pf_estimator {

/// Factors on the process noises for an odometry sample covering dt_s when they are stated for
/// samples interval_s apart (PfParams::process_noise_interval_s): `rate` = sqrt(interval / dt) on a
/// rate noise (m/s, rad/s), `diffusion` = sqrt(dt / interval) on an additive per-sample diffusion
/// (m, rad); each then adds the same variance per second at any dt. Exactly 1.0 when dt_s ==
/// interval_s or interval_s is 0 (per sample) or either is not positive.
struct NoiseScales {
  double rate = 1.0;
  double diffusion = 1.0;
};
NoiseScales process_noise_scales(double interval_s, double dt_s);

class ParticleFilter {
 public:
  using PoseEstimate = pf_estimator::PoseEstimate;

  /// Validates `params` (std::invalid_argument on a bad value). In kUniformArea mode the cloud is
  /// created here (the paper's k = 0 step); in kFirstFix mode it waits for the first update().
  ParticleFilter(const PfParams& params, std::uint64_t seed);

  const PfParams& params() const { return params_; }

  /// False only in kFirstFix mode before the first fix (or initialize_*/set_particles call).
  bool initialized() const { return initialized_; }

  /// M particles uniform over the init area (heading known or uniform), weights 1/M.
  void initialize_uniform();

  /// M particles Gaussian (std init_fix_std_m) around the fix (x_m, y_m), heading as in
  /// initialize_uniform(); weights 1/M. Throws std::invalid_argument on non-finite input.
  void initialize_around(double x_m, double y_m);

  /// Propagates every particle over dt_s with the measured odometry (v_mps forward, omega_radps
  /// counter-clockwise): each particle draws its own v + N(0, odom_v_std_mps^2) and
  /// omega - k_i v + N(0, sigma_omega^2) (sigma_omega: see PfParams; both scaled to dt_s by
  /// process_noise_scales(), as is the additive diffusion), moves on the exact
  /// constant-(v, omega) arc, then gets the additive process diffusion; k_i walks with the
  /// distance travelled. dt_s == 0 changes nothing; before initialisation the call is
  /// ignored (odometry without a pose carries no position information).
  /// Throws std::invalid_argument (state untouched) on non-finite input or dt_s < 0.
  /// omega_var_radps2: the variance the odometry claims for this omega sample ((rad/s)^2, 0 = none):
  /// with use_odometry_variance the turn noise is at least its std (issue 27, finding 4).
  void predict(double v_mps, double omega_radps, double dt_s, double omega_var_radps2 = 0.0);

  /// Checks the fix against the cloud first (gate_probability): an inconsistent fix is rejected
  /// and changes nothing but the inconsistency monitor; when that says the filter is lost
  /// (PfParams::recovery_nis) the cloud is redrawn around the last fixes (recover()). Otherwise:
  /// weights the particles with the position fix (z_x_m, z_y_m) (eq. 5, log space), normalises,
  /// computes N_eff (eq. 6) and resamples when N_eff < resample_threshold (then jitters the
  /// copies if regularization_scale > 0, see regularization.hpp); a robot that stood since the
  /// previous fix (last_update_standing()) resamples the position only. Degenerate weights are
  /// reset to uniform. In kFirstFix mode the first fix initialises the cloud around itself
  /// instead (it is not weighted a second time).
  /// Throws std::invalid_argument (state untouched) on non-finite input.
  void update(double z_x_m, double z_y_m);

  /// N_eff of the current weights (M right after resampling or initialisation).
  double effective_sample_size() const;
  /// N_eff computed by the last update() before any resampling: the value compared with N_s.
  double last_update_effective_sample_size() const { return last_update_ess_; }
  bool last_update_resampled() const { return last_update_resampled_; }
  /// True if the robot stood since the fix before the last one (mean odometry speed over the interval
  /// below standstill_speed_mps, PfParams::standstill_keeps_heading): that fix resampled the position
  /// only, every particle kept its heading and turn slip (issue 27, finding 4).
  bool last_update_standing() const { return last_update_standing_; }
  /// Number of resampling steps since construction.
  std::size_t resample_count() const { return resample_count_; }
  /// d^2 of the last fix against the cloud (consistency.hpp); 0 before the first weighted fix.
  double last_update_nis() const { return last_update_nis_; }
  /// True if the last update() rejected its fix as inconsistent (outlier or lost filter).
  bool last_update_rejected() const { return last_update_rejected_; }
  std::size_t rejected_count() const { return rejected_count_; }
  /// Number of recoveries (cloud redrawn around a fix) since construction.
  std::size_t recovery_count() const { return recovery_count_; }
  const InconsistencyMonitor& monitor() const { return monitor_; }
  /// The measurements back the belief (issue 27): confirm_fixes accepted fixes since the last
  /// (re)initialisation and, for a heading given as known, the fixes' displacement agrees with it
  /// (HeadingPriorCheck). The node publishes valid only when this holds.
  bool confirmed() const;
  const HeadingPriorCheck& heading_prior_check() const { return prior_check_; }
  /// A heading the cloud learned must agree with the fixes' track (HeadingTrackCheck,
  /// PfParams::track_check_*) once per (re)initialisation; true when it did, or when the heading
  /// was given as known (HeadingPriorCheck's business) or the check is off.
  bool track_confirmed() const { return track_confirmed_; }
  const HeadingTrackCheck& heading_track_check() const { return track_check_; }
  /// Times the track check contradicted the cloud and redrew its headings (each also a restart).
  std::size_t track_redraw_count() const { return track_redraw_count_; }
  /// Of those, the redraws after the check had passed (track_check_while_driving).
  std::size_t track_redraw_while_driving_count() const { return track_redraw_driving_count_; }
  /// Fixes after which the heading spread was widened to the track's difference (track_check_inflate_sigmas).
  std::size_t track_inflation_count() const { return track_inflation_count_; }
  /// Fixes after which the turn-slip spread was widened to the track fit's (track_check_floor).
  std::size_t track_floor_count() const { return track_floor_count_; }
  /// Weighted std of the particles' turn slips (rad/m).
  double turn_slip_std_radpm() const { return std::sqrt(turn_slip_variance()); }
  /// The track check judged while driving since the last (re)initialisation (track_check_floor
  /// applies until then).
  bool track_judged_while_driving() const { return track_judged_driving_; }
  /// Restarts because the heading spread passed track_doubt_std_rad before the track judged.
  std::size_t track_doubt_count() const { return track_doubt_count_; }
  /// The fix std per axis (m) the filter uses: estimated from the innovations
  /// (PfParams::noise_window_fixes), never below measurement_std_m.
  double measurement_std_estimate_m() const { return noise_.std_m(); }

  /// Fixes whose component-wise median centres a recovery.
  static constexpr std::size_t kRecoveryFixes = 5;

  /// Redraws every particle around (z_x_m, z_y_m) (std init_fix_std_m);
  /// recovery_uniform_heading_fraction of them get a uniform heading and a fresh turn slip
  /// (N(0, turn_slip_std_radpm^2)), the rest keep their own heading and turn slip; weights uniform. Called by update() on persistent inconsistency.
  void recover(double z_x_m, double z_y_m);

  /// Turn slip k of every particle (rad/m).
  const Eigen::ArrayXd& turn_slips() const { return turn_slip_; }

  /// Weighted mean and covariance (eq. 7, circular mean for theta).
  /// Throws std::logic_error before initialisation.
  PoseEstimate estimate() const;

  const ParticleSet& particles() const { return particles_; }
  /// Normalised weights, sum 1.
  const Eigen::ArrayXd& weights() const { return weights_; }

  /// Replaces the particle set (sizes must equal M, values finite; theta is wrapped) and the
  /// weights (finite, >= 0, positive sum; normalised here); every turn slip becomes 0. For tests
  /// and state restore.
  /// Throws std::invalid_argument, leaving the state untouched, on bad input.
  void set_particles(const ParticleSet& particles, const Eigen::ArrayXd& weights);

 private:
  double draw_heading();
  /// The track check runs after it passed (track_check_while_driving, a learned heading).
  bool track_watching() const;
  /// While driving: widens the cloud's heading (and turn slip) spread about its mean where its
  /// difference to the track's exceeds track_check_inflate_sigmas combined sigmas.
  void inflate_towards_track(double cloud_theta_rad, double cloud_theta_var);
  /// Widens the turn-slip spread about its mean to at least the track fit's std with the slip prior
  /// (track_check_floor).
  void floor_to_track();
  /// Weighted variance of the particles' turn slips ((rad/m)^2).
  double turn_slip_variance() const;
  void start_confirmation();
  /// Feeds an accepted fix to the track check until it passes (and after, with
  /// track_check_while_driving); redraws the headings on a contradiction.
  void check_heading_against_track(double z_x_m, double z_y_m);
  double noise(double std_dev);
  void reset_weights_to_uniform();
  /// keep_headings: only x and y are drawn from the weighted cloud (and jittered); every particle
  /// keeps its own heading and turn slip.
  void resample(bool keep_headings);

  PfParams params_;
  RandomEngine engine_;
  Eigen::Index num_particles_;
  bool initialized_ = false;

  ParticleSet particles_;
  Eigen::ArrayXd turn_slip_;    // rad/m, k of each particle (kept out of ParticleSet: pose only)
  Eigen::ArrayXd weights_;      // normalised
  Eigen::ArrayXd log_weights_;  // log(weights_), kept so tiny weights keep their ratios

  // Reused by resample() so the filter does not allocate after construction.
  ParticleSet resample_buffer_;
  Eigen::ArrayXd turn_slip_buffer_;
  std::vector<std::size_t> ancestor_indices_;

  double last_update_ess_;
  bool last_update_resampled_ = false;
  bool last_update_standing_ = false;
  double since_fix_distance_m_ = 0.0;  // m, odometry distance (signed) since the last fix
  double since_fix_time_s_ = 0.0;      // s, odometry time since the last fix
  std::size_t resample_count_ = 0;

  double gate_nis_;  // +inf without a gate
  InconsistencyMonitor monitor_;
  FixNoiseEstimator noise_;  // kept across recoveries: the sensor did not change
  HeadingPriorCheck prior_check_;
  HeadingTrackCheck track_check_;
  bool track_confirmed_ = true;
  bool track_learned_ = false;  // the cloud's heading was learned (not given as known): the track check applies
  std::size_t track_redraw_count_ = 0;
  std::size_t track_redraw_driving_count_ = 0;
  std::size_t track_inflation_count_ = 0;
  std::size_t track_floor_count_ = 0;
  std::size_t track_doubt_count_ = 0;
  bool track_judged_driving_ = false;
  bool floor_allowed_ = true;  // track_check_floor: since an initialisation, not a recovery  // check_drifting() judged since the last (re)initialisation
  std::size_t accepted_since_init_ = 0;  // fixes used since the last (re)initialisation
  double last_update_nis_ = 0.0;
  bool last_update_rejected_ = false;
  std::size_t rejected_count_ = 0;
  std::size_t recovery_count_ = 0;
  // The last kRecoveryFixes fixes (ring buffer), for the median a recovery is centred on.
  std::array<double, kRecoveryFixes> recent_x_{};
  std::array<double, kRecoveryFixes> recent_y_{};
  std::size_t recent_count_ = 0;
};

}  // namespace robodds::pf_estimator
