#pragma once
// How wrong is a range-rate estimate? (issue 27: every estimate carries an honest uncertainty.)
// The observer laws give no error covariance, and their error depends on the range noise, the
// sample period, the gains and the range accelerations of the moment. So it is measured: the
// slope of the least-squares line through the ranges of the last check_window_s is an independent
// estimate of the range rate at the window's mean time, unbiased for any constant range
// acceleration (the quadratic term has no slope about the window's centre). The estimate v_hat at
// that time minus the slope, d, holds the observer's error there plus the slope's own (variance
// sigma^2 / sum (t - t_mean)^2, small: 0.09 m/s for 0.5 m noise over 2 s at 50 Hz). The reported
// variance is the larger of two exponentially weighted means of d^2 (time constants fast_tau_s
// and slow_tau_s): conservative by the slope's variance, quick to follow a growing error, slow to
// forget one. d is measured check_window_s / 2 late, so an error that grows now shows after that.
// After a (re)start, until the window holds check_window_s of samples, the variance is the start's
// own (start_std_mps^2: the rate prior, or the restart line's slope error) and the weighted means
// start from it.
// Pure: times in s, ranges in m, rates in m/s.

#include <cstddef>
#include <deque>

#include "common/param_table.hpp"

namespace robodds::range_rate_observer {

struct RateUncertaintyParams {
  double check_window_s = 2.0;  // s, span of the least-squares line d is measured against
  double fast_tau_s = 0.5;      // s, time constant of the quickly following mean of d^2
  double slow_tau_s = 5.0;      // s, time constant of the slowly forgetting mean of d^2
  /// m/s: std of the true range rate at the first sample, where the observer starts at 0 m/s
  /// (what it knows of the rate before it has measured one). The node's 0 means the robot's top
  /// speed / 3: about a fixed target |range rate| <= speed, so 3 stds cover any rate.
  double initial_rate_std_mps = 2.0;  // the library's default; the node's is 0 (see above)
  /// m/s: the smallest std reported. Below ~1 mm/s the "error" of a noise-free estimate is the
  /// evaluation's own resolution (the truth's rate at a step against a range sampled at that step),
  /// not the observer's: the Kalman filter's steady error is ~1e-4 m/s, which the check line
  /// agrees with to ~1e-5, and a std of 1e-5 called it over-confident (issue 28).
  double min_std_mps = 0.001;
  /// m/s^2, the largest |range acceleration| expected: a restart starts from the slope of a line
  /// through restart_window_s of ranges, the rate at the window's centre, which is off the rate at
  /// its end by up to this times half the window. Not a YAML key: the observer node sets it from
  /// the scenario's range-acceleration bound (system::range_accel_bound).
  double range_accel_mps2 = 0.0;

  /// Throws std::invalid_argument "key: requirement (got value)" for the first bad field.
  void validate() const;
};

/// Units, ranges and descriptions of the YAML keys of RateUncertaintyParams (the one source).
const params::ParamTable<RateUncertaintyParams>& rate_uncertainty_param_table();

class RateUncertainty {
 public:
  explicit RateUncertainty(RateUncertaintyParams params = {});

  /// The estimate (re)starts: its rate error has std start_std_mps (m/s) until measured; the
  /// window is emptied (the estimate before the restart says nothing of the one after).
  void restart(double start_std_mps);
  /// A valid estimate v_hat_mps at time_s (s, increasing), the range range_m measured then.
  void add(double time_s, double range_m, double v_hat_mps);
  /// The standard deviation (m/s) of the rate error: see the file comment.
  double std_mps() const;
  /// How many times d was measured since the last restart (0: std_mps() is the start's).
  std::size_t checks() const { return checks_; }
  const RateUncertaintyParams& params() const { return params_; }

 private:
  struct Sample {
    double t = 0.0;  // s
    double r = 0.0;  // m
    double v = 0.0;  // m/s, the estimate at t
  };
  /// v_hat at time t inside the window, linear between the two samples around it.
  double estimate_at(double t) const;

  RateUncertaintyParams params_;
  std::deque<Sample> window_;
  double fast_var_ = 0.0;  // (m/s)^2
  double slow_var_ = 0.0;  // (m/s)^2
  double last_check_s_ = 0.0;
  std::size_t checks_ = 0;
};

}  // namespace robodds::range_rate_observer
