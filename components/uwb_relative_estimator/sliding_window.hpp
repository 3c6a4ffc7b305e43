#pragma once
// The sliding-window pose graph of paper 3, eq. (2): the poses of N robots over the last `window`
// epochs, constrained by each robot's odometry between consecutive epochs and by the single-epoch
// UWB relative poses of eq. (1); least squares with constant information matrices (as the paper:
// "set to constants"), solved by Levenberg-Marquardt as Ceres runs it (the edges are Ceres cost
// functions) but with the window's structure: ordered by epoch the normal equations are block
// tridiagonal, so each step is one block elimination along the window (issue 29). Poses live in an
// arbitrary common frame whose gauge is fixed by holding robot 0's oldest pose in the window; only
// relative poses are meaningful.

#include <cstddef>
#include <deque>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "common/model/pose2.hpp"
#include "common/param_table.hpp"

namespace robodds::uwb_relative_estimator {

/// Standard deviations behind the constant information matrices (diagonal, 1/sigma^2).
/// Units, ranges and one-line descriptions of these fields: window_weights_param_table() in
/// sliding_window.cpp (the one source; its doc() prints them). Defaults: the member initialisers.
struct WindowWeights {
  double odometry_xy_std_m = 0.02;
  double odometry_theta_std_rad = 0.01;
  double uwb_xy_std_m = 0.3;
  double uwb_theta_std_rad = 0.1;
  /// Throws std::invalid_argument "key: requirement (got value)".
  void validate() const;
};

/// Keys, units, ranges and descriptions of WindowWeights (defaults: the initialisers above).
const params::ParamTable<WindowWeights>& window_weights_param_table();

/// One UWB relative pose of eq. (1): robot `other` in robot `own`'s frame.
struct PairMeasurement {
  std::size_t own = 0;
  std::size_t other = 0;
  model::Pose2 pose;
};

class SlidingWindowGraph {
 public:
  /// num_robots >= 2, window >= 2 epochs (the paper: 30). Throws std::invalid_argument.
  SlidingWindowGraph(std::size_t num_robots, std::size_t window, WindowWeights weights);

  /// Adds an epoch: `odometry[i]` is robot i's motion since the previous epoch in its own frame
  /// (ignored for the first epoch), `uwb` the relative poses measured at this epoch (any pairs,
  /// possibly none). The new poses are initialised by dead reckoning, or from a UWB measurement to
  /// robot 0 at the first epoch. The oldest epoch drops out once the window is full. Throws
  /// std::invalid_argument (wrong count, unknown or equal robots, non-finite values) and then
  /// changes nothing.
  void add_epoch(const std::vector<model::Pose2>& odometry, const std::vector<PairMeasurement>& uwb);

  /// Re-estimates every pose in the window (Levenberg-Marquardt: Ceres' steps, radius and default
  /// tolerances, initial trust region 1e6). Returns false if it did not converge within 50
  /// iterations; the poses are still its best estimate.
  bool optimize();

  /// Moves every pose of robot `robot` in the window so that at the newest epoch it sits at
  /// `relative` in robot `own`'s frame (own != robot), and at earlier epochs back along its own
  /// odometry. For a robot whose poses were a guess: its first measurement came after the window
  /// started, or none was in the window for a while. Throws std::invalid_argument (nothing changed)
  /// on an empty window, bad indices or a non-finite pose.
  void place_robot(std::size_t robot, std::size_t own, const model::Pose2& relative);
  /// Robot `other` in robot `own`'s frame at the newest epoch.
  model::Pose2 latest_relative(std::size_t own, std::size_t other) const;

  std::size_t epochs() const { return epochs_.size(); }

 private:
  struct Epoch {
    std::vector<model::Pose2> poses;        // per robot, common frame
    std::vector<model::Pose2> odometry;     // per robot, increment into this epoch
    std::vector<PairMeasurement> uwb;
  };

  std::size_t num_robots_;
  std::size_t window_;
  WindowWeights weights_;
  std::deque<Epoch> epochs_;
  // optimize()'s per-epoch blocks, kept between calls: allocated and first touched anew in every
  // call they were a sixth of its time (malloc, page faults; issue 29, session 13).
  std::vector<Eigen::MatrixXd> diagonal_;
  std::vector<Eigen::MatrixXd> inverse_;
  std::vector<Eigen::LLT<Eigen::MatrixXd>> factor_;
};

}  // namespace robodds::uwb_relative_estimator
