#pragma once
// Regularisation ("roughening") after resampling, an extension beyond the paper.
//
// Resampling copies particles, so after a few cycles the cloud holds many identical headings
// and cannot move towards a heading it no longer contains: from a uniform initial heading the
// filter then locks onto an early, wrong guess. The regularised particle filter (Musso, Oudjane
// & Le Gland, 2001) resamples from a kernel density instead: every copy is jittered with
// N(0, h^2 S), S the weighted covariance of the cloud before resampling and h a bandwidth.
// The jitter shrinks with the cloud, so it is large while the heading is unknown and small once
// it has converged - unlike a fixed process noise, which has to be large all the time.

#include <Eigen/Core>

namespace robodds::pf {

/// Optimal Gaussian-kernel bandwidth for M particles in d = 3 dimensions ([x, y, theta]):
/// h_opt = (4 / (M (d + 2)))^(1 / (d + 4)). 0.361 for M = 1000. Requires M >= 1.
double optimal_kernel_bandwidth(Eigen::Index num_particles);

/// A matrix L with L L^T = bandwidth^2 * covariance, from the eigen-decomposition (negative
/// eigenvalues from rounding are clamped to 0, so a degenerate cloud gives no jitter along
/// that direction instead of failing like a Cholesky factorisation would).
Eigen::Matrix3d kernel_square_root(const Eigen::Matrix3d& covariance, double bandwidth);

}  // namespace robodds::pf
