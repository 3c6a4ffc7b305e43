#pragma once
// Parameters of the circumnavigation guidance law (issue 10, paper 2 section 2; the law is ours,
// the paper gives none: see README.md). The orbit radius is not a parameter: it comes with the
// mission (TargetAssignment.desired_radius).

#include "common/param_table.hpp"

namespace robodds::circumnavigation_controller {

// Units, ranges and one-line descriptions of these fields: guidance_param_table() in
// guidance_params.cpp (the one source). Defaults: the member initialisers, the values the
// prototype of issue 10 converged with from 768 of 768 start poses.
struct GuidanceParams {
  double cruise_speed_mps = 10.0;  // V0
  double approach_gain = 0.8;      // rdot_des = -approach_gain V sat((r - R) / approach_width)
  double approach_width_m = 100.0;
  double heading_gain = 0.02;  // omega = V/R + heading_gain (rdot - rdot_des), in rad/s per m/s
  double max_turn_rate_radps = 0.15;
  double spacing_gain = 0.5;        // V = V0 (1 + sat(spacing_gain (g+ - g-) / (2 pi / n)))
  double spacing_saturation = 0.3;  // |V / V0 - 1| <= spacing_saturation
  double max_accel_mps2 = 0.5;      // |dV/dt| limit of the speed command
  /// The first command cruises at V0: the robots are moving when the mission starts (the paper's
  /// robots move at a constant speed), so the observer's first transient, from rate 0, is the
  /// paper's. false: from rest. After a stop (zero commands) the law starts again from rest.
  bool start_cruising = true;

  /// Throws std::invalid_argument "key: requirement (got value)" for the first bad field.
  void validate() const;
};

const params::ParamTable<GuidanceParams>& guidance_param_table();

/// The largest speed the law commands: V0 (1 + spacing_saturation).
double max_commanded_speed(const GuidanceParams& params);

}  // namespace robodds::circumnavigation_controller
