#pragma once
// A range-rate observer fed by sampled ranges: the estimator state (s_hat, v_hat) integrated with
// explicit Euler between samples, the correction computed from the error at the previous sample.
// One class for both of paper 2's observers; `Law` picks the right-hand side (observer_laws.hpp).

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>

#include "common/number_text.hpp"
#include "components/range_rate_observer/observer_laws.hpp"

namespace robodds::range_rate {

struct RangeRateEstimate {
  double time_s = 0.0;
  double range_m = 0.0;    // s_hat
  double rate_mps = 0.0;   // v_hat, the range-rate estimate (positive: the range grows)
};

template <class Params, ObserverDerivative (*Derivative)(const Params&, double, double)>
class RangeRateObserver {
 public:
  /// Throws std::invalid_argument (from Params::validate) for bad gains.
  explicit RangeRateObserver(Params params) : params_(std::move(params)) { params_.validate(); }

  /// Feeds the range measured at time_s (s, strictly increasing) and returns the estimate at
  /// time_s. The first sample starts the observer at (range, rate 0). A non-finite input or a
  /// time that does not advance throws std::invalid_argument and leaves the state unchanged.
  ///
  /// Restart: when the range moved between two samples by more than restart_jump_m beyond what
  /// the rate estimate explains, |(s_k - s_k-1) - v_hat dt| (a new target or range source), the
  /// observer starts again at the new range and the next sample sets the rate from the difference
  /// of the two. Measured differences, not s_hat, are compared, so the range error of a converging
  /// observer never triggers it, and a fast target at a coarse sample rate restarts once at most
  /// (while v_hat is still far off), not on every sample.
  RangeRateEstimate update(double time_s, double range_m) {
    if (!std::isfinite(time_s) || !std::isfinite(range_m)) {
      throw std::invalid_argument("range-rate observer: non-finite input (time_s " + shortest_text(time_s) +
                                  ", range_m " + shortest_text(range_m) + ")");
    }
    if (!started_) {
      start_at(time_s, range_m, 0.0);
      return estimate_;
    }
    if (!(time_s > estimate_.time_s)) {
      throw std::invalid_argument("range-rate observer: time must advance (got " + shortest_text(time_s) + " s after " +
                                  shortest_text(estimate_.time_s) + " s)");
    }
    const double dt = time_s - estimate_.time_s;
    if (rate_from_next_difference_) {
      start_at(time_s, range_m, (range_m - last_range_m_) / dt);
      return estimate_;
    }
    const double unexplained_m = (range_m - last_range_m_) - estimate_.rate_mps * dt;
    if (params_.restart_jump_m > 0.0 && std::abs(unexplained_m) > params_.restart_jump_m) {
      ++restarts_;
      start_at(time_s, range_m, estimate_.rate_mps);
      rate_from_next_difference_ = true;
      return estimate_;
    }
    const ObserverDerivative derivative = Derivative(params_, estimate_.rate_mps, error_m_);
    estimate_.time_s = time_s;
    estimate_.range_m += dt * derivative.range_mps;
    estimate_.rate_mps += dt * derivative.rate_mps2;
    error_m_ = range_m - estimate_.range_m;
    last_range_m_ = range_m;
    return estimate_;
  }

  bool started() const { return started_; }
  /// How many times a range jump above restart_jump_m restarted the observer.
  std::size_t restarts() const { return restarts_; }
  const Params& params() const { return params_; }

 private:
  void start_at(double time_s, double range_m, double rate_mps) {
    estimate_ = {time_s, range_m, rate_mps};
    error_m_ = 0.0;
    last_range_m_ = range_m;
    rate_from_next_difference_ = false;
    started_ = true;
  }

  Params params_;
  RangeRateEstimate estimate_;
  double error_m_ = 0.0;       // s - s_hat at the last sample, m
  double last_range_m_ = 0.0;  // the last measured range, m
  bool rate_from_next_difference_ = false;  // just restarted: the next sample sets the rate
  bool started_ = false;
  std::size_t restarts_ = 0;
};

using SuperTwistingObserver = RangeRateObserver<SuperTwistingParams, &super_twisting_derivative>;
using LinearRangeRateObserver = RangeRateObserver<LinearObserverParams, &linear_derivative>;

}  // namespace robodds::range_rate
