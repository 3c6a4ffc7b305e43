#include "components/range_rate_observer/observer_laws.hpp"

#include <cmath>

namespace robodds::range_rate_observer {
namespace {

double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

}  // namespace

ObserverDerivative super_twisting_derivative(const SuperTwistingParams& params, double rate_estimate_mps,
                                             double range_error_m) {
  const double e = range_error_m;
  return {rate_estimate_mps + params.a * std::sqrt(std::abs(e)) * sign(e) + params.d * e,
          params.b * sign(e) + params.c * e};
}

ObserverDerivative linear_derivative(const LinearObserverParams& params, double rate_estimate_mps,
                                     double range_error_m) {
  return {rate_estimate_mps + params.k1 * range_error_m, params.k2 * range_error_m};
}

}  // namespace robodds::range_rate_observer
