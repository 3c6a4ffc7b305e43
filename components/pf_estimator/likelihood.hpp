#pragma once
// Measurement weighting of paper 1, eq. (5), kept in log space.
//
// Eq. (5) is the Gaussian density of the position fix z around each particle,
//   w~_i = 1 / (2 pi s_x s_y) * exp(-((z_x - x_i)^2 / 2 s_x^2 + (z_y - y_i)^2 / 2 s_y^2)),
// here with s_x = s_y = s. The constant factor cancels in the normalisation, so only the
// exponent is accumulated. Far from the cloud the exponent reaches -1e5 and exp() underflows to
// 0 for every particle; subtracting the largest log-weight before exp() avoids that.

#include <Eigen/Core>

#include "components/pf_estimator/particle_set.hpp"

namespace robodds::pf_estimator {

/// log_weights[i] += -((z_x - x_i)^2 + (z_y - y_i)^2) / (2 s^2). z in m (world frame), s in m.
void add_position_log_likelihood(const ParticleSet& particles, double z_x_m, double z_y_m,
                                 double measurement_std_m, Eigen::ArrayXd& log_weights);

/// Normalises in place: weights = exp(log_weights - max) / sum, and log_weights is shifted so
/// that it holds log(weights) again (keeps magnitudes bounded over many updates while keeping
/// the relative weight of particles whose weight underflows in linear space). Relative weights
/// below the smallest normal double (~2.2e-308) become exactly 0.
/// Returns false, leaving the arrays unspecified, when the weights are degenerate (every
/// log-weight -inf or NaN, or a non-finite sum); the caller then resets them.
bool normalize_log_weights(Eigen::ArrayXd& log_weights, Eigen::ArrayXd& weights);

}  // namespace robodds::pf_estimator
