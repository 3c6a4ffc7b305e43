#pragma once
// Parameters of the particle-filter pose estimator (paper 1, section 2). Pure data plus
// validation: no YAML here. pf_param_table() is also the source of the node's keys and of
// config/pf_estimator.params.yaml. validate() starts each error message with the key it
// rejects, e.g. "num_particles: must be >= 1 (got 0)".
//
// Noise values are standard deviations, not variances. "Per prediction" values are applied once
// per predict() call, so they should be tuned for the odometry rate that drives the filter
// (50 Hz in the reference scenario).

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

// Units, ranges and one-line descriptions of these fields: pf_param_table() in pf_params.cpp
// (the one source; `robodds components --params pf_estimator` prints it). Defaults: the member
// initialisers.
struct PfParams {
  int num_particles = 1000;
  /// The usual choice: M/2.
  double resample_threshold = 500.0;
  ResamplingScheme resampling = ResamplingScheme::kSystematic;

  double measurement_std_m = 1.51;

  double odom_v_std_mps = 0.05;
  double odom_omega_std_radps = 0.02;
  /// Additive. Keeps the cloud from collapsing onto a few resampled copies when odometry is very
  /// precise or the robot stands.
  double process_pos_std_m = 0.02;
  /// Additive. Small: the heading is kept diverse by the regularisation below, and a large value
  /// blurs the learned heading.
  double process_theta_std_rad = 0.0005;
  /// Regularised particle filter (regularization.hpp): after each resampling every copy is
  /// jittered with N(0, (scale * h_opt)^2 * S), S the cloud covariance. Extension beyond the
  /// paper, needed to learn an unknown heading.
  double regularization_scale = 0.5;

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
  double init_fix_std_m = 1.51;

  /// Throws std::invalid_argument naming the first offending key: the table's ranges, then
  /// resample_threshold <= num_particles, known enum values and min < max of the init area.
  void validate() const;
};

/// Keys (= field names), units, ranges and descriptions of PfParams.
const params::ParamTable<PfParams>& pf_param_table();

}  // namespace robodds::pf
