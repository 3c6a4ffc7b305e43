#pragma once
// Errors of relative pose estimates (paper 3, issue 11): each stage of the relative estimator
// (uwb, window, pf, pf_baseline, odometry) gives, per robot i and peer j, the pose of j in i's
// body frame; its error is taken against the truth model::between(pose_i, pose_j) of the two
// robots' true world poses at the same step, and pooled over all (i, j) pairs of the stage.
// Pure: poses in m and rad, times in s; the evaluator node matches samples to truth by step.

#include <cstddef>
#include <map>
#include <string>

#include "common/model/pose2.hpp"

namespace robodds::evaluator {

/// Error of one estimate of j in i's frame against the truth.
struct RelativePoseError {
  double position_m = 0.0;  // Euclidean distance between estimated and true position of j in i's frame
  double heading_rad = 0.0; // estimate - truth heading, wrapped to (-pi, pi]
};

/// The true pose of j in i's frame (model::between) and the error of `estimate` against it.
RelativePoseError relative_pose_error(const model::Pose2& world_i, const model::Pose2& world_j,
                                      const model::Pose2& estimate);

/// Running mean and POPULATION standard deviation (divided by n, as numpy.std's default) of a
/// series, by Welford's update: one pass, constant memory, no cancellation of large sums.
class RunningStats {
 public:
  void add(double value);
  std::size_t count() const { return count_; }
  double mean() const { return mean_; }  // 0 when empty
  double stddev() const;                 // population standard deviation; 0 when count < 2

 private:
  std::size_t count_ = 0;
  double mean_ = 0.0;
  double m2_ = 0.0;  // sum of squared deviations from the running mean
};

/// What summary.json's metrics.stages.<stage> holds.
struct RelativeStageStats {
  std::size_t epochs = 0;          // valid estimates counted (t >= metrics_after_s)
  std::size_t invalid_epochs = 0;  // estimates with valid = false (t >= metrics_after_s)
  double position_error_m_mean = 0.0;
  double position_error_m_std = 0.0;     // population std
  double heading_error_deg_mean = 0.0;   // of |wrapped heading error|, degrees
  double heading_error_deg_std = 0.0;    // population std of |wrapped heading error|, degrees
};

/// Per stage (by name), the errors of its estimates from t >= metrics_after_s on, pooled over
/// all (i, j) pairs. Estimates are accumulated in the order given: feed them in an order fixed by
/// the data (step, then pair), so the figures are bit-identical wherever the run is deployed.
class RelativePoseMetrics {
 public:
  /// Times t_s >= metrics_after_s count (with 1 ns of tolerance: times come from step * step_s).
  explicit RelativePoseMetrics(double metrics_after_s) : after_s_(metrics_after_s) {}

  /// A stage that may have no estimate at all: listed by stages() with zero epochs.
  void expect_stage(const std::string& stage) { stages_.try_emplace(stage); }
  /// A valid estimate of stage `stage` at time t_s: `estimate` is j in i's frame, world_i and
  /// world_j the true world poses of i and j at the estimate's step.
  void add_valid(const std::string& stage, double t_s, const model::Pose2& world_i, const model::Pose2& world_j,
                 const model::Pose2& estimate);
  /// An estimate flagged not valid (the stage had no usable estimate): counted, never measured.
  void add_invalid(const std::string& stage, double t_s);

  /// Every stage seen or expected, by name.
  std::map<std::string, RelativeStageStats> stages() const;

 private:
  struct Stage {
    RunningStats position_m;
    RunningStats heading_rad;  // |wrapped error|
    std::size_t invalid = 0;
  };
  bool counts(double t_s) const { return t_s >= after_s_ - 1e-9; }

  double after_s_;
  std::map<std::string, Stage> stages_;
};

}  // namespace robodds::evaluator
