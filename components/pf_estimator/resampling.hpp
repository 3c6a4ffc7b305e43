#pragma once
// Resampling and degeneracy measure of the particle filter (paper 1, step 4 and eq. (6)).
// Free functions over weight vectors: no particle state here.
//
// Every resampler returns M ancestor indices (M = number of weights) in ascending order; the
// expected number of copies of particle i is M * w_i (unbiased). Systematic resampling has the
// lowest variance (each count is floor or ceil of M w_i); residual keeps the floor(M w_i) copies
// and randomises only the remainder. The `_into` variants write into
// a caller-owned vector so the filter can reuse its capacity and avoid allocating per update.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "common/random.hpp"

namespace robodds::pf_estimator {

/// N_eff of eq. (6), read with normalised weights: 1 / sum_i w_i^2. Computed as
/// (sum w)^2 / sum w^2, which equals it for normalised weights and is insensitive to a last-bit
/// normalisation error. Uniform weights give M, a one-hot vector gives 1; 0 for empty/all-zero.
double effective_sample_size(const Eigen::ArrayXd& normalized_weights);

/// Systematic resampling: pointers (u0 + j/M), j = 0..M-1, into the cumulative weights.
/// u0 must be in [0, 1/M) (draw it as uniform01 / M). Weights must be finite, >= 0, with a
/// positive sum (they are rescaled by their sum, so a rounding error in normalisation is harmless).
/// Throws std::invalid_argument otherwise.
std::vector<std::size_t> systematic_resample(const Eigen::ArrayXd& normalized_weights, double u0);
void systematic_resample_into(const Eigen::ArrayXd& normalized_weights, double u0,
                              std::vector<std::size_t>& indices);

/// Residual resampling (Liu & Chen): floor(M w_i) deterministic copies of particle i, then the
/// remaining R = M - sum floor(M w_i) indices drawn multinomially from the residuals
/// M w_i - floor(M w_i). Draws exactly R uniform01 values from `engine` (none when every M w_i is
/// an integer). Same preconditions as systematic_resample. Note: a *systematic* draw of the
/// remainder would be identical to plain systematic resampling, hence the multinomial remainder.
std::vector<std::size_t> residual_resample(const Eigen::ArrayXd& w, RandomEngine& engine);
void residual_resample_into(const Eigen::ArrayXd& w, RandomEngine& engine,
                            std::vector<std::size_t>& indices);

}  // namespace robodds::pf_estimator
