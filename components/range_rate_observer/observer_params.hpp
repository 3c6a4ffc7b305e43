#pragma once
// Parameters of the range-rate observers of paper 2 (Lin & Zhang 2020, "A range rate observer
// based on ranging signal"). Pure data plus validation: field names are the YAML keys, and
// validate() starts each message with the key it rejects. The parameter tables below are also the
// one source of the keys for a future node.
//
// Signals: range in m, range rate in m/s, time in s. The gains act on the range error
// e = s - s_hat, which sets their units.

#include "common/param_table.hpp"

namespace robodds::range_rate_observer {

/// Sliding-mode (generalised super-twisting) observer, eq. (1) as read in README.md:
///   s_hat' = v_hat + a |e|^(1/2) sgn(e) + d e,   v_hat' = b sgn(e) + c e,   e = s - s_hat.
/// Defaults: the gains that NOTES.md found to converge in ~3 s.
/// Units, ranges and one-line descriptions of these fields: super_twisting_param_table() in
/// observer_params.cpp (the one source; its doc() prints them).
struct SuperTwistingParams {
  double a = 2.12;
  /// The paper's b > 3/4 mu1: below the largest |range acceleration| the estimate is no longer
  /// exact.
  double b = 2.2;
  /// The "+c x1" printed in eq. (2) makes the error grow; see README.md.
  double c = 1.0;
  double d = 1.0;
  /// A range step between two samples that the rate misses by more than restart_sigmas times
  /// its estimated spread means a new target or range source: the observer restarts at the new
  /// range instead of a transient of hundreds of m/s. The spread is estimated online from the
  /// steps themselves (robustly, never below noise_floor_m), so range noise alone does not
  /// restart it, whatever the sensor's true noise (issue 27). 7 at the 0.5 m floor: 4.95 m, the
  /// fixed 5 m of before.
  double restart_sigmas = 7.0;
  /// The range noise (sigma, m) the sensor is configured with: the floor of the online estimate.
  double noise_floor_m = 0.5;
  /// After a restart the state is re-initialised from a least-squares line through the samples
  /// of this long a window (s); the estimate is not valid until the window is full.
  double restart_window_s = 0.5;

  /// Throws std::invalid_argument "key: requirement (got value)" for the first bad field.
  void validate() const;
};

/// The linear baseline observer, eq. (9) as read in README.md:
///   r_hat' = v_hat + k1 (r - r_hat),   v_hat' = k2 (r - r_hat).
/// Critically damped at k1 = 2 w, k2 = w^2; the defaults (w = 1.5 rad/s) converge about as fast
/// as the super-twisting defaults.
/// Units, ranges and one-line descriptions of these fields: linear_observer_param_table() in
/// observer_params.cpp (the one source; its doc() prints them). Defaults: the member initialisers.
struct LinearObserverParams {
  double k1 = 3.0;
  double k2 = 2.25;
  double restart_sigmas = 7.0;    // as SuperTwistingParams::restart_sigmas
  double noise_floor_m = 0.5;     // as SuperTwistingParams::noise_floor_m
  double restart_window_s = 0.5;  // as SuperTwistingParams::restart_window_s

  void validate() const;
};

/// Issue 28, beyond the paper: a Kalman filter on range, range rate and range acceleration
/// (kalman_law.hpp), the range modelled as driven by white jerk of spectral density q.
/// Units, ranges and one-line descriptions: kalman_observer_param_table() in observer_params.cpp.
struct KalmanObserverParams {
  /// q (m^2/s^5). Small: the steady noise floor of a slowly changing range rate (at 0.5 m of
  /// range noise and 50 Hz, 0.001 gives the linear observer's floor); the acceleration state
  /// carries the manoeuvres without the lag of a two-state observer (README.md, "Kalman filter").
  double jerk_psd_m2ps5 = 0.001;
  /// The range acceleration's std at a (re)start (m/s^2): the acceleration the mission allows.
  double initial_accel_std_mps2 = 2.2;
  /// The smallest range noise (sigma, m) the filter weighs a range by: it weighs by the online
  /// estimate (the configured noise_floor_m until that is trained), which may be ~0 for a
  /// noise-free sensor.
  double min_range_sigma_m = 0.01;
  double restart_sigmas = 7.0;    // as SuperTwistingParams::restart_sigmas
  double noise_floor_m = 0.5;     // as SuperTwistingParams::noise_floor_m
  double restart_window_s = 0.5;  // as SuperTwistingParams::restart_window_s

  void validate() const;
};

const params::ParamTable<SuperTwistingParams>& super_twisting_param_table();
const params::ParamTable<LinearObserverParams>& linear_observer_param_table();
const params::ParamTable<KalmanObserverParams>& kalman_observer_param_table();

}  // namespace robodds::range_rate_observer
