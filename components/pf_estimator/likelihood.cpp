#include "components/pf_estimator/likelihood.hpp"

#include <cmath>
#include <limits>

namespace robodds::pf_estimator {

void add_position_log_likelihood(const ParticleSet& particles, double z_x_m, double z_y_m,
                                 double measurement_std_m, Eigen::ArrayXd& log_weights) {
  const double inv_two_variance = 0.5 / (measurement_std_m * measurement_std_m);
  log_weights -=
      ((particles.x - z_x_m).square() + (particles.y - z_y_m).square()) * inv_two_variance;
}

bool normalize_log_weights(Eigen::ArrayXd& log_weights, Eigen::ArrayXd& weights) {
  if (log_weights.size() == 0) {
    return false;
  }
  const double max_log_weight = log_weights.maxCoeff();
  if (!std::isfinite(max_log_weight)) {
    return false;
  }
  // Eigen 3.4's vectorised exp() clamps its argument at about -708 and so returns ~5.6e-309
  // (not 0) for anything smaller, -inf included: a particle with zero weight would come back
  // to life. Flush everything below the smallest normal double to an exact 0.
  static const double kMinLogWeight = std::log(std::numeric_limits<double>::min());
  const auto shifted = log_weights - max_log_weight;
  weights = (shifted < kMinLogWeight).select(0.0, shifted.exp());
  // The largest term is exp(0) = 1, so the sum is >= 1 unless NaN crept in.
  const double sum = weights.sum();
  if (!std::isfinite(sum) || !(sum >= 1.0)) {
    return false;
  }
  weights /= sum;
  log_weights -= max_log_weight + std::log(sum);
  return true;
}

}  // namespace robodds::pf_estimator
