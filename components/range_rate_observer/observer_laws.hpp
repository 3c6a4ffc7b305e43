#pragma once
// The right-hand sides of paper 2's two observers: given the rate estimate v_hat (m/s) and the
// range error e = s - s_hat (m), the time derivatives of s_hat (m/s) and v_hat (m/s^2).

#include "components/range_rate_observer/observer_params.hpp"

namespace robodds::range_rate_observer {

/// A law's state carried dt ahead on its own model, without a range (a lost sample).
struct LawPrediction {
  double range_m = 0.0;  // m
  double rate_mps = 0.0;  // m/s
};

struct ObserverDerivative {
  double range_mps = 0.0;   // d s_hat / dt
  double rate_mps2 = 0.0;   // d v_hat / dt
};

/// Eq. (1) as read in README.md (generalised super-twisting):
///   s_hat' = v_hat + a |e|^(1/2) sgn(e) + d e,   v_hat' = b sgn(e) + c e.
/// sgn(0) = 0.
ObserverDerivative super_twisting_derivative(const SuperTwistingParams& params, double rate_estimate_mps,
                                             double range_error_m);

/// Eq. (9) as read in README.md (linear baseline):  r_hat' = v_hat + k1 e,   v_hat' = k2 e.
ObserverDerivative linear_derivative(const LinearObserverParams& params, double rate_estimate_mps,
                                     double range_error_m);

}  // namespace robodds::range_rate_observer
