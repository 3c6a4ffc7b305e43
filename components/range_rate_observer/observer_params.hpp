#pragma once
// Parameters of the range-rate observers of paper 2 (Lin & Zhang 2020, "A range rate observer
// based on ranging signal"). Pure data plus validation: field names are the YAML keys, and
// validate() starts each message with the key it rejects. Defaults: the member initialisers;
// keys, units, ranges, descriptions: the parameter tables below (one source for a future node).
//
// Units: range in m, range rate in m/s, time in s. The gains act on the range error e = s - s_hat
// (m), so a is in m^(1/2)/s, b in m/s^2, c in 1/s^2, d in 1/s; k1 in 1/s and k2 in 1/s^2.

#include "common/param_table.hpp"

namespace robodds::range_rate {

/// Sliding-mode (generalised super-twisting) observer, eq. (1) as read in README.md:
///   s_hat' = v_hat + a |e|^(1/2) sgn(e) + d e,   v_hat' = b sgn(e) + c e,   e = s - s_hat.
/// Defaults: the gains that NOTES.md found to converge in ~3 s.
struct SuperTwistingParams {
  /// 0 < a < 2.5 (the paper's range from its Lyapunov analysis).
  double a = 2.12;
  /// b > 0, and above the largest |range acceleration| the observer must follow (the paper's
  /// b > 3/4 mu1); below it the estimate is no longer exact.
  double b = 2.2;
  /// c > 0. The "+c x1" printed in eq. (2) makes the error grow; see README.md.
  double c = 1.0;
  /// d >= 0, the linear term of J in eq. (3); d = 0 is the plain super-twisting observer.
  double d = 1.0;
  /// A range step between two samples that the rate estimate misses by more than this (a new
  /// target or range source) restarts the observer at the new range, instead of a transient of
  /// hundreds of m/s; the next sample sets the rate. m, >= 0; 0 = never restart.
  double restart_jump_m = 5.0;

  /// Throws std::invalid_argument "key: requirement (got value)" for the first bad field.
  void validate() const;
};

/// The linear baseline observer, eq. (9) as read in README.md:
///   r_hat' = v_hat + k1 (r - r_hat),   v_hat' = k2 (r - r_hat).
/// Critically damped at k1 = 2 w, k2 = w^2; the defaults (w = 1.5 rad/s) converge about as fast
/// as the super-twisting defaults.
struct LinearObserverParams {
  double k1 = 3.0;   // 1/s, > 0
  double k2 = 2.25;  // 1/s^2, > 0
  double restart_jump_m = 5.0;  // m, >= 0, as above

  void validate() const;
};

const params::ParamTable<SuperTwistingParams>& super_twisting_param_table();
const params::ParamTable<LinearObserverParams>& linear_observer_param_table();

}  // namespace robodds::range_rate
