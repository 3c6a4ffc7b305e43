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
//
// Jitter alone widens the cloud by (1 + h^2) at every resampling, also along a direction no
// measurement observes (the heading of a robot that stands still: issue 12 measured 2 -> 100
// degrees in 350 s). The filter therefore shrinks each copy towards the cloud mean first
// (Liu & West, 2001): x' = m + a (x - m) + jitter with a = sqrt(1 - h^2) keeps the mean and the
// covariance of the cloud, so regularisation diversifies without widening.

#include <Eigen/Core>

namespace robodds::pf_estimator {

/// Optimal Gaussian-kernel bandwidth for M particles in d = 3 dimensions ([x, y, theta]):
/// h_opt = (4 / (M (d + 2)))^(1 / (d + 4)). 0.361 for M = 1000. Requires M >= 1.
double optimal_kernel_bandwidth(Eigen::Index num_particles);

/// A matrix L with L L^T = bandwidth^2 * covariance, from the eigen-decomposition (negative
/// eigenvalues from rounding are clamped to 0, so a degenerate cloud gives no jitter along
/// that direction instead of failing like a Cholesky factorisation would).
Eigen::Matrix3d kernel_square_root(const Eigen::Matrix3d& covariance, double bandwidth);

/// a = sqrt(1 - h^2), the shrinkage towards the mean that makes a kernel of bandwidth h keep the
/// covariance (see above). Bandwidths >= 1 give 0 (the copies are redrawn around the mean).
double kernel_shrinkage(double bandwidth);

}  // namespace robodds::pf_estimator
