#pragma once
// Parameters of the relative-pose particle filter of paper 3, eq. (3)-(6), and of the paper's
// baseline [22] (the same filter weighted directly by the UWB ranges). Pure data plus validation:
// no YAML here. relative_pf_param_table() is the one source of keys, units, ranges and
// descriptions; validate() throws std::invalid_argument("key: requirement (got value)").
//
// All noise values are standard deviations. "Per epoch" values are applied once per predict()
// call, i.e. per 10 Hz estimator epoch (issue 11).

#include "common/param_table.hpp"

namespace robodds::uwb_relative_estimator {

// Defaults: the member initialisers (issue 11 and the paper: 500 particles, lambda_d 0.3 m,
// lambda_theta 0.1 rad, odometry noise 0.005 m / 0.003 rad per epoch, resampling after every update).
struct RelativePfParams {
  int num_particles = 500;
  /// Eq. (4) noise, drawn per particle and applied to each robot's odometry increment
  /// (x and y in that robot's frame): both robots' motion uncertainty enters the relative pose.
  double odometry_xy_std_m = 0.005;
  double odometry_theta_std_rad = 0.003;
  /// Eq. (5)-(6), read as standard deviations: position distance and wrapped heading difference
  /// between the measured relative pose and a particle. Also the spread of the initial cloud.
  double lambda_d_m = 0.3;
  double lambda_theta_rad = 0.1;
  /// Baseline [22]: each of the K x L ranges weighs a particle with N(r_kl - d(x); range_std_m).
  double range_std_m = 0.3;
  /// Resample when N_eff < fraction x num_particles; 1 = after every update (the paper).
  double resample_ess_fraction = 1.0;

  /// Throws std::invalid_argument naming the first offending key: the table's ranges, then
  /// resample_ess_fraction <= 1.
  void validate() const;
};

/// Keys (= field names), units, ranges and descriptions of RelativePfParams.
const params::ParamTable<RelativePfParams>& relative_pf_param_table();

}  // namespace robodds::uwb_relative_estimator
