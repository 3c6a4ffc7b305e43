#pragma once
// Relative-pose particle filter of paper 3, eq. (3)-(6), and the paper's baseline [22].
//
// State: the pose x of robot j in robot i's body frame (model::Pose2: x forward, y left, m;
// theta counter-clockwise, rad, wrapped to (-pi, pi]), one particle per hypothesis.
// Cycle, once per estimator epoch (10 Hz in issue 11):
//   predict(own_increment, other_increment)  eq. (4): x <- inverse(m_i) * x * m_j, with per-particle
//                                            noise on both increments;
//   update_with_pose(z)                      eq. (5)-(6): weights from a relative-pose measurement
//                                            (the sliding window's estimate, or a single epoch's);
//   or update_with_ranges(own, other, r)     baseline [22]: weights from the K x L UWB ranges;
//   then resampling (systematic, components/pf_estimator/resampling.hpp) when N_eff is below
//   resample_ess_fraction x S, by default after every update as the paper does;
//   estimate()                               weighted mean, circular mean for the heading.
// Both observation models may be mixed on one filter, but the paper's filter uses the first and
// the baseline [22] the second. Log-weights throughout, so 16 ranges cannot underflow them.
//
// Randomness: every call that draws takes the caller's RandomEngine (nodes seed it with
// ctx.seed_for(name)), so the same engine state and inputs give bit-identical particles.
// Not thread-safe; one instance per (robot, peer) pair.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "common/model/pose2.hpp"
#include "common/random.hpp"
#include "components/pf_estimator/particle_set.hpp"
#include "components/pf_estimator/pose_estimate.hpp"
#include "components/uwb_relative_estimator/relative_pf_params.hpp"
#include "common/model/uwb_array.hpp"

namespace robodds::uwb_relative_estimator {

class RelativePoseFilter {
 public:
  /// Validates `params` (std::invalid_argument naming the key). The filter starts uninitialised.
  explicit RelativePoseFilter(const RelativePfParams& params);

  const RelativePfParams& params() const { return params_; }

  /// False until initialize() or the first update_with_pose().
  bool initialized() const { return initialized_; }

  /// S particles Gaussian around `pose` (std lambda_d_m on x and y, lambda_theta_rad on theta),
  /// weights 1/S. For the baseline, `pose` is e.g. the first single-epoch solve of eq. (1).
  /// Throws std::invalid_argument (state untouched) on a non-finite pose.
  void initialize(const model::Pose2& pose, RandomEngine& engine);

  /// Eq. (4) for one epoch. `own_increment` is robot i's motion since the previous epoch in its own
  /// frame (pose of i at t in i at t-1), `other_increment` robot j's in j's frame. Each particle
  /// draws its own noisy copies of both increments (odometry_xy_std_m on x and y,
  /// odometry_theta_std_rad on theta) and moves to between(m_i', x) composed with m_j', i.e.
  /// inverse(m_i') * x * m_j'. Ignored before initialisation (odometry alone carries no relative
  /// pose). Throws std::invalid_argument (state and engine untouched) on non-finite input.
  void predict(const model::Pose2& own_increment, const model::Pose2& other_increment, RandomEngine& engine);

  /// Eq. (5)-(6): multiplies each weight by the likelihood of `measured` (pose of j in i's frame),
  /// normalises and resamples (see the class comment). Before initialisation it initialises around
  /// `measured` instead (the measurement is not weighted a second time).
  /// Throws std::invalid_argument (state and engine untouched) on a non-finite measurement.
  void update_with_pose(const model::Pose2& measured, RandomEngine& engine);

  /// Baseline [22]: weights from the ranges, prod_{k,l} N(r_kl - d(x, C_i^k, C_j^l); range_std_m),
  /// then as update_with_pose. `ranges_m` is K x L (row k: node k of `own` = robot i, column l: node
  /// l of `other` = robot j). Throws std::invalid_argument (state and engine untouched) on a wrong
  /// size or a negative or non-finite range, std::logic_error before initialisation (the ranges
  /// alone give no starting cloud: initialise from a solve of eq. 1).
  void update_with_ranges(const model::UwbArray& own, const model::UwbArray& other, const Eigen::MatrixXd& ranges_m,
                          RandomEngine& engine);

  /// Weighted mean of x and y, circular mean of theta, and the weighted covariance
  /// (pf_estimator::weighted_pose_estimate). Throws std::logic_error before initialisation.
  pf_estimator::PoseEstimate estimate() const;
  /// The mean of estimate() as a pose.
  model::Pose2 estimated_pose() const;

  const pf_estimator::ParticleSet& particles() const { return particles_; }
  /// Normalised weights, sum 1 (uniform right after resampling).
  const Eigen::ArrayXd& weights() const { return weights_; }

  /// N_eff = 1 / sum w^2 computed by the last update before any resampling.
  double last_update_effective_sample_size() const { return last_update_ess_; }
  bool last_update_resampled() const { return last_update_resampled_; }
  std::size_t resample_count() const { return resample_count_; }

 private:
  /// Adds log_likelihood_ to the log-weights, normalises and resamples if N_eff asks for it.
  void apply_log_likelihood(RandomEngine& engine);
  void resample(RandomEngine& engine);
  void set_uniform_weights();
  model::Pose2 particle(Eigen::Index s) const { return {particles_.x[s], particles_.y[s], particles_.theta[s]}; }

  RelativePfParams params_;
  Eigen::Index num_particles_;
  bool initialized_ = false;

  pf_estimator::ParticleSet particles_;
  Eigen::ArrayXd weights_;        // normalised
  Eigen::ArrayXd log_weights_;    // log(weights_), so tiny weights keep their ratios
  Eigen::ArrayXd log_likelihood_; // scratch of one update, filled before the state is touched

  // Reused by resample() so the filter does not allocate per epoch.
  pf_estimator::ParticleSet resample_buffer_;
  std::vector<std::size_t> ancestor_indices_;

  double last_update_ess_ = 0.0;
  bool last_update_resampled_ = false;
  std::size_t resample_count_ = 0;
};

}  // namespace robodds::uwb_relative_estimator
