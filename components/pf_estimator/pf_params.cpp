#include "components/pf_estimator/pf_params.hpp"

#include <stdexcept>
#include <string>

#include "common/angle.hpp"
#include "common/number_text.hpp"
#include "common/param_checks.hpp"
#include "components/pf_estimator/consistency.hpp"

namespace robodds::pf_estimator {
namespace {

using param_checks::reject;

void require_ordered(std::string_view min_key, double min_value, std::string_view max_key,
                     double max_value) {
  if (!(max_value > min_value)) {
    reject(max_key, "must be > " + std::string(min_key) + " = " + shortest_text(min_value), max_value);
  }
}

}  // namespace

ResamplingScheme resampling_scheme_from_string(std::string_view text) {
  if (text == "systematic") {
    return ResamplingScheme::kSystematic;
  }
  if (text == "residual") {
    return ResamplingScheme::kResidual;
  }
  throw std::invalid_argument("resampling: must be \"systematic\" or \"residual\" (got \"" +
                              std::string(text) + "\")");
}

std::string to_string(ResamplingScheme scheme) {
  return scheme == ResamplingScheme::kResidual ? "residual" : "systematic";
}

InitMode init_mode_from_string(std::string_view text) {
  if (text == "uniform_area") {
    return InitMode::kUniformArea;
  }
  if (text == "first_fix") {
    return InitMode::kFirstFix;
  }
  throw std::invalid_argument("init_mode: must be \"uniform_area\" or \"first_fix\" (got \"" +
                              std::string(text) + "\")");
}

std::string to_string(InitMode mode) {
  return mode == InitMode::kFirstFix ? "first_fix" : "uniform_area";
}

const params::ParamTable<PfParams>& pf_param_table() {
  using params::finite;
  using params::non_negative;
  using params::positive;
  using params::shown_as;
  static const params::ParamTable<PfParams> table =
      params::ParamTable<PfParams>()
          .add("num_particles", &PfParams::num_particles, "", params::at_least(1), "M, the number of particles")
          .add("resample_threshold", &PfParams::resample_threshold, "particles", shown_as(positive(), "(0, num_particles]"),
               "N_s: resample when the effective sample size N_eff < N_s")
          .add_enum("resampling", &PfParams::resampling, resampling_scheme_from_string, to_string,
                    {"systematic", "residual"}, "how a degenerate particle set is redrawn")
          .add("measurement_std_m", &PfParams::measurement_std_m, "m", positive(),
               "s_x = s_y in eq. (5); 1.51 ~ sqrt(2.28) matches the sensor; the floor of the estimated fix noise")
          .add("noise_window_fixes", &PfParams::noise_window_fixes, "fixes", shown_as(params::at_least(0), ">= 0; 0 = assume measurement_std_m"),
               "the fix noise is the running median of the innovations over this many fixes (likelihood, gate, monitor)")
          .add("process_noise_interval_s", &PfParams::process_noise_interval_s, "s",
               shown_as(non_negative(), ">= 0; 0 = per sample"),
               "the process noises are stated for odometry samples this far apart; scaled by each sample's dt (same variance per second at any odometry rate)")
          .add("odom_v_std_mps", &PfParams::odom_v_std_mps, "m/s", non_negative(),
               "noise added to the odometry speed per particle and prediction (for a sample of process_noise_interval_s)")
          .add("odom_omega_std_radps", &PfParams::odom_omega_std_radps, "rad/s", non_negative(),
               "turn-rate noise per particle and prediction, constant part")
          .add("odom_omega_std_per_mps", &PfParams::odom_omega_std_per_mps, "rad/m", non_negative(),
               "turn-rate noise per particle and prediction, x |v| (wheel errors grow with speed)")
          .add("odom_omega_std_fraction", &PfParams::odom_omega_std_fraction, "", non_negative(),
               "turn-rate noise per particle and prediction, x |omega|")
          .add("use_odometry_variance", &PfParams::use_odometry_variance, "", params::any<bool>(),
               "true: the turn-rate noise is at least the std each odometry sample claims (var_omega)")
          .add("standstill_keeps_heading", &PfParams::standstill_keeps_heading, "", params::any<bool>(),
               "true: a fix after standing resamples the position only; every particle keeps its heading and turn slip")
          .add("standstill_speed_mps", &PfParams::standstill_speed_mps, "m/s", non_negative(),
               "below this mean odometry speed between two fixes the robot counts as standing (the fixes cannot see its heading)")
          .add("process_pos_std_m", &PfParams::process_pos_std_m, "m", non_negative(),
               "extra x and y diffusion per prediction")
          .add("process_theta_std_rad", &PfParams::process_theta_std_rad, "rad", non_negative(),
               "extra heading diffusion per prediction (widens the heading at standstill too)")
          .add("turn_slip_std_radpm", &PfParams::turn_slip_std_radpm, "rad/m", non_negative("0 with a 0 walk = no turn-slip state"),
               "initial spread of each particle's turn slip k: omega is corrected to omega - k v")
          .add("turn_slip_walk_std_radpm", &PfParams::turn_slip_walk_std_radpm, "rad/m", non_negative(),
               "random walk of k per sqrt(m) travelled")
          .add("regularization_scale", &PfParams::regularization_scale, "", non_negative("0 = plain resampling, as the paper"),
               "x the optimal kernel bandwidth of the covariance-keeping jitter after resampling")
          .add("gate_probability", &PfParams::gate_probability, "", params::in_half_open_interval(0.0, 1.0),
               "chi-square gate: a fix beyond this quantile of the 2-dof NIS is rejected; 0 = no gate")
          .add("recovery_nis", &PfParams::recovery_nis, "", shown_as(non_negative("0 = never"), "0 or (2, gate quantile)"),
               "lost when the moving mean d^2 of the accepted fixes exceeds this: redraw the cloud around the fixes")
          .add("recovery_rejected_share", &PfParams::recovery_rejected_share, "", params::in_open_interval(0.0, 1.0),
               "... or when the moving share of rejected fixes exceeds this")
          .add("recovery_window_fixes", &PfParams::recovery_window_fixes, "fixes", shown_as(positive(), ">= 1"),
               "length of those moving averages")
          .add("recovery_bias_nis", &PfParams::recovery_bias_nis, "", non_negative("0 = off"),
               "... or when the normalised moving mean of the accepted innovations exceeds this (fixes on one side)")
          .add("recovery_bias_window_fixes", &PfParams::recovery_bias_window_fixes, "fixes", shown_as(positive(), ">= 1"),
               "length of that moving mean")
          .add("recovery_uniform_heading_fraction", &PfParams::recovery_uniform_heading_fraction, "",
               shown_as(non_negative(), "[0, 1]"), "share of the redrawn particles with a uniform heading")
          .add_enum("init_mode", &PfParams::init_mode, init_mode_from_string, to_string, {"uniform_area", "first_fix"},
                    "uniform over the init area (the paper) or around the first position fix")
          .add("init_area_min_x", &PfParams::init_area_min_x, "m", finite(), "uniform_area: smallest x of the area, world frame")
          .add("init_area_max_x", &PfParams::init_area_max_x, "m", shown_as(finite(), "> init_area_min_x"), "uniform_area: largest x")
          .add("init_area_min_y", &PfParams::init_area_min_y, "m", finite(), "uniform_area: smallest y")
          .add("init_area_max_y", &PfParams::init_area_max_y, "m", shown_as(finite(), "> init_area_min_y"), "uniform_area: largest y")
          .add("init_theta_known", &PfParams::init_theta_known, "", params::any<bool>(),
               "true: every particle starts with init_theta_rad (the paper's assumption)")
          .add("init_theta_rad", &PfParams::init_theta_rad, "rad", finite(), "initial heading if known, world frame")
          .add("prior_heading_tolerance_rad", &PfParams::prior_heading_tolerance_rad, "rad",
               shown_as(non_negative("0 = the prior is trusted"), "[0, pi/2)"),
               "a known initial heading counts once the fixes moved within this of it; beyond: redraw the cloud. Also the most a learned heading may differ from the fixes' track (track_check_*)")
          .add("confirm_fixes", &PfParams::confirm_fixes, "fixes", params::at_least(0),
               "accepted fixes after a (re)initialisation before the estimate can be valid")
          .add("track_check_window_fixes", &PfParams::track_check_window_fixes, "fixes",
               shown_as(params::at_least(0), "0 or >= 20; 0 = off"),
               "a learned heading is checked against the rotation of the dead-reckoned track onto the last this many fixes before confirmed()")
          .add("track_check_sigmas", &PfParams::track_check_sigmas, "", positive(),
               "the cloud's heading agrees with the track's within this many combined sigmas, or its headings are redrawn around the track's")
          .add("track_check_heading_std_rad", &PfParams::track_check_heading_std_rad, "rad", positive(),
               "the track must know the heading this well (std from its fit) before it judges the cloud")
          .add("track_check_cloud_std_rad", &PfParams::track_check_cloud_std_rad, "rad", positive(),
               "the check passes when the cloud agrees and its heading std is below this (the node's valid_max_heading_std_rad); the heading std of a redraw")
          .add("track_check_while_driving", &PfParams::track_check_while_driving, "", params::any<bool>(),
               "after it passed, a learned heading stays checked against the track of the last fixes (the odometry's turn slip fitted too, its drift counted); a contradiction redraws the headings (a restart)")
          .add("track_redraw_widens_position", &PfParams::track_redraw_widens_position, "", params::any<bool>(),
               "a redraw of the headings by the track check also widens the positions about their mean to at least the estimated fix noise per axis")
          .add("track_check_floor", &PfParams::track_check_floor, "", params::any<bool>(),
               "while driving, until the track first judges, the cloud's turn-slip spread is at least the track fit's (with the turn-slip prior)")
          .add("track_doubt_std_rad", &PfParams::track_doubt_std_rad, "rad", non_negative("0 = never"),
               "with track_check_floor: a heading std above this before the track judged ends the confirmation (a restart); the node's valid_keep_max_heading_std_rad")
          .add("track_check_inflate_sigmas", &PfParams::track_check_inflate_sigmas, "", non_negative("0 = off"),
               "while driving, the heading (and turn slip) spread is widened until the cloud is within this many combined sigmas of the track's; 0 = off")
          .add("init_fix_std_m", &PfParams::init_fix_std_m, "m", positive(), "spread around the first fix (first_fix mode)");
  return table;
}

void PfParams::validate() const {
  pf_param_table().check_ranges(*this);
  if (resample_threshold > num_particles) {
    reject("resample_threshold", "must be in (0, num_particles]", resample_threshold);
  }
  if (resampling != ResamplingScheme::kSystematic && resampling != ResamplingScheme::kResidual) {
    reject("resampling", "must be systematic or residual", static_cast<int>(resampling));
  }
  if (init_mode != InitMode::kUniformArea && init_mode != InitMode::kFirstFix) {
    reject("init_mode", "must be uniform_area or first_fix", static_cast<int>(init_mode));
  }
  if (!(recovery_window_fixes >= 1.0)) {
    reject("recovery_window_fixes", "must be >= 1", recovery_window_fixes);
  }
  if (!(recovery_bias_window_fixes >= 1.0)) {
    reject("recovery_bias_window_fixes", "must be >= 1", recovery_bias_window_fixes);
  }
  if (!(prior_heading_tolerance_rad < 0.5 * kPi)) {
    reject("prior_heading_tolerance_rad", "must be in [0, pi/2)", prior_heading_tolerance_rad);
  }
  if (track_check_window_fixes != 0 && track_check_window_fixes < 20) {
    reject("track_check_window_fixes", "must be 0 (off) or >= 20", track_check_window_fixes);
  }
  if (!(recovery_uniform_heading_fraction <= 1.0)) {
    reject("recovery_uniform_heading_fraction", "must be in [0, 1]", recovery_uniform_heading_fraction);
  }
  if (recovery_nis > 0.0) {
    if (!(recovery_nis > InconsistencyMonitor::kConsistentMeanNis)) {
      reject("recovery_nis", "must be 0 or > 2, the mean NIS of a consistent filter", recovery_nis);
    }
    if (gate_probability > 0.0 && !(recovery_nis < chi_square_2dof_quantile(gate_probability))) {
      reject("recovery_nis",
             "must be below the gate " + shortest_text(chi_square_2dof_quantile(gate_probability)) +
                 " (accepted fixes never average above it)",
             recovery_nis);
    }
  }
  // The area and the fix spread are checked whatever the mode, so a config stays valid when
  // only init_mode is switched.
  require_ordered("init_area_min_x", init_area_min_x, "init_area_max_x", init_area_max_x);
  require_ordered("init_area_min_y", init_area_min_y, "init_area_max_y", init_area_max_y);
}

}  // namespace robodds::pf_estimator
