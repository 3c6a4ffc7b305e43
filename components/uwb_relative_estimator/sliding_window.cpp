#include "components/uwb_relative_estimator/sliding_window.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include <ceres/ceres.h>

#include "common/angle.hpp"
#include "common/param_checks.hpp"
#include "components/uwb_relative_estimator/window_edge.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

bool finite(const model::Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }

model::Pose2 inverse(const model::Pose2& a_b) { return model::between(a_b, model::Pose2{}); }

}  // namespace

const params::ParamTable<WindowWeights>& window_weights_param_table() {
  using W = WindowWeights;
  static const params::ParamTable<W> table =
      params::ParamTable<W>("Sliding-window pose graph of paper 3, eq. (2): constant information matrices.")
          .add("odometry_xy_std_m", &W::odometry_xy_std_m, "m", params::positive(), "odometry increment position std per epoch")
          .add("odometry_theta_std_rad", &W::odometry_theta_std_rad, "rad", params::positive(),
               "odometry increment heading std per epoch")
          .add("uwb_xy_std_m", &W::uwb_xy_std_m, "m", params::positive(), "single-epoch UWB relative position std")
          .add("uwb_theta_std_rad", &W::uwb_theta_std_rad, "rad", params::positive(),
               "single-epoch UWB relative heading std");
  return table;
}

void WindowWeights::validate() const { window_weights_param_table().check_ranges(*this); }

SlidingWindowGraph::SlidingWindowGraph(std::size_t num_robots, std::size_t window, WindowWeights weights)
    : num_robots_(num_robots), window_(window), weights_(weights) {
  if (num_robots_ < 2) {
    param_checks::reject("num_robots", "must be >= 2", static_cast<double>(num_robots_));
  }
  if (window_ < 2) {
    param_checks::reject("window", "must be >= 2 epochs", static_cast<double>(window_));
  }
  weights_.validate();
}

void SlidingWindowGraph::add_epoch(const std::vector<model::Pose2>& odometry, const std::vector<PairMeasurement>& uwb) {
  if (odometry.size() != num_robots_) {
    throw std::invalid_argument("add_epoch: " + std::to_string(odometry.size()) + " odometry increments for " +
                                std::to_string(num_robots_) + " robots");
  }
  for (std::size_t i = 0; i < odometry.size(); ++i) {
    if (!finite(odometry[i])) {
      throw std::invalid_argument("add_epoch: odometry of robot " + std::to_string(i) + " is not finite (got " +
                                  model::to_text(odometry[i]) + ")");
    }
  }
  for (const PairMeasurement& m : uwb) {
    if (m.own >= num_robots_ || m.other >= num_robots_ || m.own == m.other) {
      throw std::invalid_argument("add_epoch: UWB pair (" + std::to_string(m.own) + ", " + std::to_string(m.other) +
                                  ") is not two different robots of " + std::to_string(num_robots_));
    }
    if (!finite(m.pose)) {
      throw std::invalid_argument("add_epoch: UWB pose of pair (" + std::to_string(m.own) + ", " +
                                  std::to_string(m.other) + ") is not finite (got " + model::to_text(m.pose) + ")");
    }
  }
  Epoch epoch;
  epoch.odometry = odometry;
  epoch.uwb = uwb;
  epoch.poses.resize(num_robots_);
  if (epochs_.empty()) {
    // Robot 0 defines the frame; the others start where a UWB measurement to robot 0 puts them.
    for (std::size_t i = 1; i < num_robots_; ++i) {
      epoch.poses[i] = model::Pose2{static_cast<double>(i), 0.0, 0.0};
      for (const PairMeasurement& m : uwb) {
        if (m.own == 0 && m.other == i) {
          epoch.poses[i] = m.pose;
        } else if (m.own == i && m.other == 0) {
          epoch.poses[i] = inverse(m.pose);
        }
      }
    }
  } else {
    for (std::size_t i = 0; i < num_robots_; ++i) {
      epoch.poses[i] = model::compose(epochs_.back().poses[i], odometry[i]);
    }
  }
  epochs_.push_back(std::move(epoch));
  if (epochs_.size() > window_) {
    epochs_.pop_front();
  }
}

bool SlidingWindowGraph::optimize() {
  if (epochs_.empty()) {
    return true;
  }
  std::vector<std::array<double, 3>> blocks(epochs_.size() * num_robots_);
  const auto block = [&](std::size_t e, std::size_t i) { return blocks[e * num_robots_ + i].data(); };
  for (std::size_t e = 0; e < epochs_.size(); ++e) {
    for (std::size_t i = 0; i < num_robots_; ++i) {
      const model::Pose2& p = epochs_[e].poses[i];
      blocks[e * num_robots_ + i] = {p.x, p.y, p.theta};
    }
  }
  ceres::Problem::Options problem_options;
  problem_options.disable_all_safety_checks = true;  // the edges join validated, distinct blocks (3 % less per solve)
  ceres::Problem problem(problem_options);
  const auto add_edge = [&](double* a, double* b, const model::Pose2& measured, double xy_std, double theta_std) {
    problem.AddResidualBlock(new WindowEdgeResidual(measured, xy_std, theta_std), nullptr, a, b);
  };
  for (std::size_t e = 0; e < epochs_.size(); ++e) {
    for (std::size_t i = 0; i < num_robots_ && e > 0; ++i) {
      add_edge(block(e - 1, i), block(e, i), epochs_[e].odometry[i], weights_.odometry_xy_std_m,
               weights_.odometry_theta_std_rad);
    }
    for (const PairMeasurement& m : epochs_[e].uwb) {
      add_edge(block(e, m.own), block(e, m.other), m.pose, weights_.uwb_xy_std_m, weights_.uwb_theta_std_rad);
    }
  }
  for (std::size_t e = 0; e < epochs_.size(); ++e) {
    for (std::size_t i = 0; i < num_robots_; ++i) {
      problem.AddParameterBlock(block(e, i), 3);  // a robot without any edge yet still has a block
    }
  }
  problem.SetParameterBlockConstant(block(0, 0));  // gauge: the oldest pose of robot 0
  ceres::Solver::Options options;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;  // a chain of 3x3 blocks: sparse
  options.max_num_iterations = 50;
  // The window is warm-started (every pose from the previous solve, the new epoch by dead reckoning),
  // so the first step is taken nearly as Gauss-Newton's: 2.2 rather than 3.1 evaluations per solve
  // on average (issue 29, docs/performance.md "Paper 3 with more robots"). Convergence is judged
  // by the same tolerances; experiment 2's window errors moved by < 1e-5 m and 1e-4 deg.
  options.initial_trust_region_radius = 1e6;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  for (std::size_t e = 0; e < epochs_.size(); ++e) {
    for (std::size_t i = 0; i < num_robots_; ++i) {
      const double* p = block(e, i);
      epochs_[e].poses[i] = {p[0], p[1], wrap_angle(p[2])};
    }
  }
  return summary.termination_type == ceres::CONVERGENCE;
}

void SlidingWindowGraph::place_robot(std::size_t robot, std::size_t own, const model::Pose2& relative) {
  if (epochs_.empty()) {
    throw std::invalid_argument("place_robot: no epoch added yet");
  }
  if (robot >= num_robots_ || own >= num_robots_ || robot == own) {
    throw std::invalid_argument("place_robot: robots (" + std::to_string(robot) + ", " + std::to_string(own) +
                                ") are not two different robots of " + std::to_string(num_robots_));
  }
  if (!finite(relative)) {
    throw std::invalid_argument("place_robot: pose is not finite (got " + model::to_text(relative) + ")");
  }
  epochs_.back().poses[robot] = model::compose(epochs_.back().poses[own], relative);
  for (std::size_t e = epochs_.size() - 1; e > 0; --e) {
    // The odometry of epoch e leads from e - 1 to e: undo it.
    epochs_[e - 1].poses[robot] = model::compose(epochs_[e].poses[robot], inverse(epochs_[e].odometry[robot]));
  }
}

model::Pose2 SlidingWindowGraph::latest_relative(std::size_t own, std::size_t other) const {
  if (epochs_.empty()) {
    throw std::invalid_argument("latest_relative: no epoch added yet");
  }
  if (own >= num_robots_ || other >= num_robots_) {
    throw std::invalid_argument("latest_relative: robots (" + std::to_string(own) + ", " + std::to_string(other) +
                                ") are not both among the " + std::to_string(num_robots_));
  }
  return model::between(epochs_.back().poses[own], epochs_.back().poses[other]);
}

}  // namespace robodds::uwb_relative_estimator
