#pragma once
// Parameters of the particle-filter pose estimator (paper 1, section 2). Pure data plus
// validation: no YAML here. The defaults are the member initialisers; keys, units, ranges and
// descriptions are in pf_param_table() (pf_params.cpp), the one source of the node's keys and of
// config/pf_estimator.params.yaml. validate() starts each error message with the key it
// rejects, e.g. "num_particles: must be >= 1 (got 0)".
//
// Units: SI throughout (m, s, rad). Noise values are standard deviations, not variances.
// "Per prediction" values are applied once per predict() call, so they should be tuned for the
// odometry rate that drives the filter (50 Hz in the reference scenario).

#include <string>
#include <string_view>

#include "common/param_table.hpp"

namespace robodds::pf {

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

struct PfParams {
  /// M, number of particles (>= 1).
  int num_particles = 1000;
  /// N_s in particles: resample when N_eff < N_s. Must lie in (0, M]; the usual M/2.
  double resample_threshold = 500.0;
  ResamplingScheme resampling = ResamplingScheme::kSystematic;

  /// s_x = s_y of eq. (5), m (> 0). Default: 1.51 ~ sqrt(2.28), the paper's measurement variance.
  double measurement_std_m = 1.51;

  /// Std of the noise added to the measured forward speed, per particle and prediction, m/s (>= 0).
  double odom_v_std_mps = 0.05;
  /// Std of the noise added to the measured turn rate, per particle and prediction, rad/s (>= 0).
  double odom_omega_std_radps = 0.02;
  /// Extra additive x and y diffusion per prediction step, m (>= 0). Keeps the cloud from
  /// collapsing onto a few resampled copies when odometry is very precise or the robot stands.
  double process_pos_std_m = 0.02;
  /// Extra additive heading diffusion per prediction step, rad (>= 0). Small: the heading is
  /// kept diverse by the regularisation below, and a large value blurs the learned heading.
  double process_theta_std_rad = 0.0005;
  /// Multiplier on the optimal kernel bandwidth of the regularised particle filter
  /// (regularization.hpp): after each resampling every copy is jittered with
  /// N(0, (scale * h_opt)^2 * S), S the cloud covariance. Dimensionless, >= 0; 0 gives the
  /// paper's plain resampling. Extension beyond the paper, needed to learn an unknown heading.
  double regularization_scale = 0.5;

  InitMode init_mode = InitMode::kFirstFix;
  /// Initial area for kUniformArea, world frame, m (max > min on each axis): the paper's field.
  double init_area_min_x = 0.0;
  double init_area_max_x = 100.0;
  double init_area_min_y = 0.0;
  double init_area_max_y = 100.0;
  /// If true every particle starts with heading init_theta_rad (rad, world frame, CCW from +x);
  /// otherwise headings are uniform in (-pi, pi] and learned from motion.
  bool init_theta_known = false;
  double init_theta_rad = 0.0;
  /// Std of the initial x/y spread around the first fix for kFirstFix, m (> 0).
  double init_fix_std_m = 1.51;

  /// Throws std::invalid_argument naming the first offending key: the table's ranges, then
  /// resample_threshold <= num_particles, known enum values and min < max of the init area.
  void validate() const;
};

/// Keys (= field names), units, ranges and descriptions of PfParams.
const params::ParamTable<PfParams>& pf_param_table();

}  // namespace robodds::pf
