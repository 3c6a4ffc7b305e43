#pragma once
// Parameters of the particle-filter pose estimator (paper 1, section 2). Pure data plus
// validation: no YAML here. pf_param_table() is also the source of the node's keys and of
// config/pf_estimator.params.yaml. validate() starts each error message with the key it
// rejects, e.g. "num_particles: must be >= 1 (got 0)".
//
// Noise values are standard deviations, not variances. The process noises (odom_v_std_mps,
// odom_omega_std_*, process_pos_std_m, process_theta_std_rad) are stated for an odometry sample
// covering process_noise_interval_s and scaled by each sample's actual dt, so that they add the
// same variance per second at any odometry rate (issue 27).

#include <string>
#include <string_view>

#include "common/param_table.hpp"

namespace robodds::pf_estimator {

/// How a degenerate particle set is redrawn (see resampling.hpp).
enum class ResamplingScheme {
  kSystematic,  // one uniform offset, M evenly spaced pointers: O(M), lowest variance
  kResidual,    // deterministic floor(M w_i) copies, remainder drawn multinomially
};

/// How the particle cloud is created.
enum class InitMode {
  kUniformArea,  // uniform over [init_area_min_x, max_x] x [init_area_min_y, max_y] (paper)
  kFirstFix,     // Gaussian (init_fix_std_m) around the first position fix
};

/// "systematic" / "residual"; throws std::invalid_argument("resampling: ...") otherwise.
ResamplingScheme resampling_scheme_from_string(std::string_view text);
std::string to_string(ResamplingScheme scheme);

/// "uniform_area" / "first_fix"; throws std::invalid_argument("init_mode: ...") otherwise.
InitMode init_mode_from_string(std::string_view text);
std::string to_string(InitMode mode);

// Units, ranges and one-line descriptions of these fields: pf_param_table() in pf_params.cpp
// (the one source; `robodds components --params pf_estimator` prints it). Defaults: the member
// initialisers.
struct PfParams {
  int num_particles = 1000;
  /// The usual choice: M/2.
  double resample_threshold = 500.0;
  ResamplingScheme resampling = ResamplingScheme::kSystematic;

  double measurement_std_m = 1.51;
  /// The fix noise actually seen is estimated from the innovations (fix_noise_estimator.hpp): the
  /// running median over this many fixes, never below measurement_std_m; it replaces
  /// measurement_std_m in the likelihood, the gate and the lost-filter monitor. 0 = off (the
  /// configured noise is assumed). 300 fixes = 30 s at 10 Hz: long enough that a lost filter's
  /// large innovations (recovered within ~1-5 s) do not pass for noise.
  int noise_window_fixes = 300;

  /// The interval (s) the process noises below are stated for: a sample covering dt gets the rate
  /// noises (odom_v_std_mps, odom_omega_std_*) x sqrt(process_noise_interval_s / dt) and the
  /// additive diffusion (process_pos_std_m, process_theta_std_rad) x sqrt(dt /
  /// process_noise_interval_s): both add the same variance per second at any odometry rate (a
  /// density; at dt = process_noise_interval_s nothing changes). The odometry's claimed var_omega is
  /// a statement about its own sample and is used as it comes. 0 = per sample, whatever its dt
  /// (before issue 27: tuned for 50 Hz odometry only).
  double process_noise_interval_s = 0.02;
  double odom_v_std_mps = 0.05;
  /// Turn-rate noise per particle and prediction: odom_omega_std_radps + odom_omega_std_per_mps
  /// |v| + odom_omega_std_fraction |omega|. Wheel odometry errs in proportion to how far the
  /// wheels turn, so the noise is nearly 0 at standstill (where the heading is unobservable and
  /// must not diffuse) and covers realistic wheel errors while driving.
  double odom_omega_std_radps = 0.005;
  double odom_omega_std_per_mps = 0.02;
  double odom_omega_std_fraction = 0.02;
  /// The turn-rate noise is at least the std the odometry claims for each sample (var_omega): the
  /// simulated odometry's white wheel noise turns the heading also at standstill, where nothing
  /// else widens the unobserved heading (issue 27, finding 4). false = the wheel model only.
  bool use_odometry_variance = true;
  /// A fix after an interval in which the robot stood (the odometry's mean speed since the previous
  /// fix below standstill_speed_mps) carries no heading information: when it resamples, only the
  /// position is drawn from the weighted cloud and every particle keeps its own heading and turn
  /// slip, so repeated resampling does not thin the unobserved heading below the error's random
  /// walk (issue 27, finding 4). false = every resampling copies whole particles (before).
  bool standstill_keeps_heading = true;
  /// The robot counts as standing between two fixes when its odometry's mean speed there is below this.
  double standstill_speed_mps = 0.05;
  /// Additive. Keeps the cloud from collapsing onto a few resampled copies when odometry is very
  /// precise or the robot stands.
  double process_pos_std_m = 0.02;
  /// Additive heading diffusion; 0 by default: it would widen the heading at standstill.
  double process_theta_std_rad = 0.0;
  /// Turn-slip state k (rad/m) of every particle: the odometry turn rate is corrected to
  /// omega - k v, the error of a wheel that reads fast or slow (right wheel fast by s on track D:
  /// k = s / D). Drawn N(0, turn_slip_std_radpm^2) at initialisation; a random walk of
  /// turn_slip_walk_std_radpm per sqrt(m) travelled lets it follow a changing slip. Both 0 = no
  /// state.
  double turn_slip_std_radpm = 0.05;
  double turn_slip_walk_std_radpm = 0.0005;
  /// Regularised particle filter (regularization.hpp): after each resampling every copy is
  /// shrunk towards the mean and jittered with N(0, (scale * h_opt)^2 * S), S the cloud
  /// covariance, which keeps the covariance. Extension beyond the paper, needed to learn an
  /// unknown heading.
  double regularization_scale = 0.5;

  /// Chi-square gate: a fix whose normalised innovation squared (consistency.hpp) exceeds the
  /// 2-dof quantile of this probability is not used (an outlier). 0 = every fix is used.
  double gate_probability = 0.99;
  /// Recovery (consistency.hpp): the filter is lost when, averaged over about
  /// recovery_window_fixes fixes, more than recovery_rejected_share of the fixes are rejected or
  /// the accepted ones have a mean d^2 above recovery_nis (consistent: 2). Then the cloud is
  /// redrawn around the component-wise median of the last kRecoveryFixes fixes (robust to an
  /// outlier among them); recovery_uniform_heading_fraction of the particles get a uniform
  /// heading and a fresh turn slip, the others keep theirs. recovery_nis 0 = never recover.
  double recovery_nis = 5.0;
  double recovery_rejected_share = 0.6;
  double recovery_window_fixes = 10.0;
  /// ... or when the accepted fixes sit on one side of the estimate: the mean innovation over
  /// recovery_bias_window_fixes, normalised (consistency.hpp), exceeds recovery_bias_nis
  /// (chi-square(2) if consistent; the filter's own lag reached 6-25 in the robustness runs,
  /// a 90-degree heading error at a way-point 40-70). 0 = this criterion off.
  double recovery_bias_nis = 40.0;
  double recovery_bias_window_fixes = 50.0;
  double recovery_uniform_heading_fraction = 0.5;

  InitMode init_mode = InitMode::kFirstFix;
  /// The defaults are the paper's field.
  double init_area_min_x = 0.0;
  double init_area_max_x = 100.0;
  double init_area_min_y = 0.0;
  double init_area_max_y = 100.0;
  /// Heading CCW from +x. If init_theta_known is false, headings start uniform in (-pi, pi] and
  /// are learned from motion.
  bool init_theta_known = false;
  double init_theta_rad = 0.0;
  /// A heading given as known is confirmed by the fixes' displacement (heading_prior_check.hpp)
  /// before the filter says confirmed(); a displacement more than this off the prior's redraws
  /// the cloud (a recovery). 0 = the prior is trusted unchecked (before issue 27).
  double prior_heading_tolerance_rad = 0.5236;
  /// confirmed() also needs this many accepted fixes since the last (re)initialisation: a cloud
  /// placed around one fix, or redrawn, has not been tested against the fixes yet.
  int confirm_fixes = 10;
  /// A heading the cloud learned (not given as known) is checked against the track of the fixes
  /// before confirmed() (heading_track_check.hpp): the rotation between the dead-reckoned track and
  /// the last track_check_window_fixes accepted fixes, with its std from the fit's residuals, must
  /// know the heading to track_check_heading_std_rad and agree with the cloud's within
  /// track_check_sigmas combined sigmas and at most prior_heading_tolerance_rad (when > 0); the check passes (once per (re)initialisation) when it
  /// agrees and the cloud's heading std is below track_check_cloud_std_rad. A cloud that
  /// disagrees gets its headings redrawn around the track's (std track_check_cloud_std_rad; a
  /// restart). 0 = off (before).
  int track_check_window_fixes = 300;
  double track_check_sigmas = 3.0;
  double track_check_heading_std_rad = 0.2;
  double track_check_cloud_std_rad = 0.2;
  /// After it passed, the check keeps running while the robot drives (issue 27: with fixes 2-5x
  /// noisier than configured, 1,000 particles narrow the heading faster than the fixes justify and
  /// were 11-38 deg off at a reported 2-10 deg for 20-80 s after `valid`). The window's track is
  /// dead-reckoned again with the odometry's turn slip fitted too, independently of the cloud
  /// (HeadingTrackCheck::check_drifting()); a cloud beyond track_check_inflate_sigmas is widened
  /// (below), a contradiction (track_check_sigmas combined sigmas, at most
  /// prior_heading_tolerance_rad) redraws the headings around the track's as before `valid` (a
  /// restart: the estimate must be confirmed again). false = the check stops once passed (before).
  bool track_check_while_driving = true;
  /// While driving, a cloud that agrees with the track (within track_check_sigmas) but not within
  /// this many combined sigmas gets its heading spread widened about its mean until it does, and its
  /// turn-slip spread likewise against the fit's slip error (a cloud that learned a wrong slip bends
  /// its heading: 1,000 particles with fixes 3x noisier were 28 deg off at a reported 6 deg, and the
  /// track, which must fit the slip too, alone knew it to only 8 deg). 0 = off.
  double track_check_inflate_sigmas = 2.0;
  /// A redraw of the headings by the track check also widens the positions about their mean to at
  /// least the estimated fix noise per axis: they followed the wrong heading. false = kept (before).
  bool track_redraw_widens_position = true;
  /// While driving, the cloud's heading variance is at least the track's (check_drifting() with the
  /// filter's turn-slip prior: what the fixes of the window say about the heading now), also before
  /// the track knows the heading well enough to judge (issue 27: fixes 2-5x noisier, clouds 25-40 deg
  /// off at a reported 5-10 deg in the first ~20 s after `valid`). false = not (before).
  bool track_check_floor = true;
  /// With track_check_floor: a cloud whose heading std passes this before the track judged is no
  /// longer confirmed (a restart: the consumer may move again to learn the heading). The node's
  /// valid_keep_max_heading_std_rad. 0 = never.
  double track_doubt_std_rad = 0.35;
  double init_fix_std_m = 1.51;

  /// Throws std::invalid_argument naming the first offending key: the table's ranges, then
  /// resample_threshold <= num_particles, known enum values, min < max of the init area and a
  /// recovery_nis 0 or between the consistent mean 2 and the gate.
  void validate() const;
};

/// Keys (= field names), units, ranges and descriptions of PfParams.
const params::ParamTable<PfParams>& pf_param_table();

}  // namespace robodds::pf_estimator
