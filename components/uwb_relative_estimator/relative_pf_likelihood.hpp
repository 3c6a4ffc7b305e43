#pragma once
// Observation models of the relative-pose particle filter (paper 3), as log-likelihoods up to a
// constant (the normalisers of eq. (5) cancel when the weights are normalised):
//   - eq. (5)-(6): a relative-pose measurement z (the sliding window's estimate, or a single
//     epoch's) against a particle x, both the pose of robot j in robot i's frame;
//   - the baseline [22]: the K x L node-to-node ranges against the ranges the particle predicts.
// Free functions over one particle; the filter (relative_pf.hpp) checks the inputs once per update.

#include <Eigen/Core>

#include "common/model/pose2.hpp"
#include "common/model/uwb_array.hpp"
#include "components/uwb_relative_estimator/relative_pose_solver.hpp"

namespace robodds::uwb_relative_estimator {

/// log P(z | x) of eq. (5)-(6) read with lambda_d and lambda_theta as standard deviations:
/// -1/2 [ ((z.x - x.x)^2 + (z.y - x.y)^2) / lambda_d^2 + wrap(z.theta - x.theta)^2 / lambda_theta^2 ].
double pose_log_likelihood(const model::Pose2& particle, const model::Pose2& measured, double lambda_d_m,
                           double lambda_theta_rad);

/// log prod_{k,l} N(r_kl - d(x, C_i^k, C_j^l); 0, range_std^2) up to a constant, d = predicted_range
/// (relative_pose.hpp). `ranges_m` is K x L: row k node k of `own` (robot i), column l node l of
/// `other` (robot j); the sizes are the caller's to check (require_valid_ranges, relative_pose_solver.hpp).
double range_log_likelihood(const model::Pose2& particle, const model::UwbArray& own, const model::UwbArray& other,
                            const Eigen::MatrixXd& ranges_m, double range_std_m);

/// Throws std::invalid_argument("<caller>: measured pose is not finite (got x=.., y=.., theta=..)").
void require_finite_pose(const char* caller, const model::Pose2& pose);

}  // namespace robodds::uwb_relative_estimator
