#include "components/uwb_relative_estimator/relative_pose_solver.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include <ceres/ceres.h>

#include "common/angle.hpp"
#include "common/param_checks.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

/// One range between node k of robot i and node l of robot j: residual r_kl - d(x).
struct RangeResidual {
  Eigen::Vector2d node_i;
  Eigen::Vector2d node_j;
  double range_m;

  template <class T>
  bool operator()(const T* const pose, T* residual) const {
    residual[0] = T(range_m) - predicted_range(pose[0], pose[1], pose[2], node_i, node_j);
    return true;
  }
};

/// Every range of the epoch in one residual block (row-major k, l), each residual as RangeResidual's:
/// for plain least squares, where the loss does not tell the ranges apart (issue 29: one block
/// instead of K x L, less of Ceres' per-block work).
struct AllRangesResidual {
  const UwbArray* own;
  const UwbArray* other;
  const Eigen::MatrixXd* ranges_m;

  template <class T>
  bool operator()(const T* const pose, T* residual) const {
    const std::size_t cols = other->nodes_m.size();
    for (std::size_t k = 0; k < own->nodes_m.size(); ++k) {
      for (std::size_t l = 0; l < cols; ++l) {
        residual[k * cols + l] = T((*ranges_m)(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l))) -
                                 predicted_range(pose[0], pose[1], pose[2], own->nodes_m[k], other->nodes_m[l]);
      }
    }
    return true;
  }
};

ceres::LossFunction* make_loss(const SolverOptions& options) {
  switch (options.loss) {
    case RobustLoss::kHuber:
      return new ceres::HuberLoss(options.loss_scale_m);
    case RobustLoss::kSoftL1:
      return new ceres::SoftLOneLoss(options.loss_scale_m);
    case RobustLoss::kNone:
      break;
  }
  return nullptr;
}

/// One Levenberg-Marquardt solve from `start`.
SolverResult solve_from(const UwbArray& own, const UwbArray& other, const Eigen::MatrixXd& ranges_m, model::Pose2 start,
                        const SolverOptions& options) {
  std::array<double, 3> pose{start.x, start.y, start.theta};
  ceres::Problem problem;
  if (options.loss == RobustLoss::kNone) {
    auto* cost = new ceres::AutoDiffCostFunction<AllRangesResidual, ceres::DYNAMIC, 3>(
        new AllRangesResidual{&own, &other, &ranges_m}, static_cast<int>(ranges_m.size()));
    problem.AddResidualBlock(cost, nullptr, pose.data());
  } else {
    for (Eigen::Index k = 0; k < ranges_m.rows(); ++k) {
      for (Eigen::Index l = 0; l < ranges_m.cols(); ++l) {
        auto* cost = new ceres::AutoDiffCostFunction<RangeResidual, 1, 3>(
            new RangeResidual{own.nodes_m[static_cast<std::size_t>(k)], other.nodes_m[static_cast<std::size_t>(l)], ranges_m(k, l)});
        problem.AddResidualBlock(cost, make_loss(options), pose.data());
      }
    }
  }
  ceres::Solver::Options solver;
  solver.minimizer_type = ceres::TRUST_REGION;
  solver.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.logging_type = ceres::SILENT;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  SolverResult result;
  result.pose = {pose[0], pose[1], wrap_angle(pose[2])};
  result.final_cost = summary.final_cost;
  result.starts = 1;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  return result;
}

}  // namespace

void require_valid_ranges(const char* caller, const UwbArray& own, const UwbArray& other, const Eigen::MatrixXd& ranges_m) {
  if (own.nodes_m.empty() || other.nodes_m.empty()) {
    throw std::invalid_argument(std::string(caller) + ": both arrays need at least one node (got " +
                                std::to_string(own.nodes_m.size()) + " and " + std::to_string(other.nodes_m.size()) + ")");
  }
  if (ranges_m.rows() != static_cast<Eigen::Index>(own.nodes_m.size()) ||
      ranges_m.cols() != static_cast<Eigen::Index>(other.nodes_m.size())) {
    throw std::invalid_argument(std::string(caller) + ": ranges are " + std::to_string(ranges_m.rows()) + " x " +
                                std::to_string(ranges_m.cols()) + ", the arrays need " +
                                std::to_string(own.nodes_m.size()) + " x " + std::to_string(other.nodes_m.size()));
  }
  for (Eigen::Index k = 0; k < ranges_m.rows(); ++k) {
    for (Eigen::Index l = 0; l < ranges_m.cols(); ++l) {
      if (!(ranges_m(k, l) >= 0.0) || !std::isfinite(ranges_m(k, l))) {
        param_checks::reject(std::string(caller) + ": range (" + std::to_string(k) + ", " + std::to_string(l) + ")",
                             "must be >= 0 and finite", ranges_m(k, l));
      }
    }
  }
}

RobustLoss robust_loss_from_string(std::string_view text) {
  if (text == "none") return RobustLoss::kNone;
  if (text == "huber") return RobustLoss::kHuber;
  if (text == "soft_l1") return RobustLoss::kSoftL1;
  param_checks::reject("loss", "must be none, huber or soft_l1", text);
}

std::string to_string(RobustLoss loss) {
  switch (loss) {
    case RobustLoss::kNone:
      return "none";
    case RobustLoss::kHuber:
      return "huber";
    case RobustLoss::kSoftL1:
      return "soft_l1";
  }
  return "unknown";
}

const params::ParamTable<SolverOptions>& solver_param_table() {
  using O = SolverOptions;
  static const params::ParamTable<O> table =
      params::ParamTable<O>("Single-epoch UWB-array relative pose (paper 3, eq. 1), Levenberg-Marquardt.")
          .add_enum("loss", &O::loss, robust_loss_from_string, to_string, {"none", "huber", "soft_l1"},
                    "robust loss on the range residuals (none = the paper)")
          .add("loss_scale_m", &O::loss_scale_m, "m", params::positive(),
               "residuals beyond this count linearly (about 2-3 x the range noise std)")
          .add("start_directions", &O::start_directions, "", params::at_least(1),
               "cold start: directions on the circle of the mean range")
          .add("start_headings", &O::start_headings, "", params::at_least(1), "cold start: headings per direction")
          .add("max_iterations", &O::max_iterations, "", params::at_least(1),
               "Levenberg-Marquardt iterations per start");
  return table;
}

void SolverOptions::validate() const { solver_param_table().check_ranges(*this); }

SolverResult solve_relative_pose(const UwbArray& own, const UwbArray& other, const Eigen::MatrixXd& ranges_m,
                                 const std::optional<model::Pose2>& initial, const SolverOptions& options) {
  options.validate();
  require_valid_ranges("solve_relative_pose", own, other, ranges_m);
  if (initial) {
    if (!std::isfinite(initial->x) || !std::isfinite(initial->y) || !std::isfinite(initial->theta)) {
      throw std::invalid_argument("solve_relative_pose: initial pose is not finite (got " + model::to_text(*initial) + ")");
    }
    return solve_from(own, other, ranges_m, *initial, options);
  }
  const double radius = ranges_m.mean();
  SolverResult best;
  best.final_cost = std::numeric_limits<double>::infinity();
  int starts = 0;
  for (int d = 0; d < options.start_directions; ++d) {
    const double bearing = 2.0 * kPi * d / options.start_directions;
    for (int h = 0; h < options.start_headings; ++h) {
      const model::Pose2 start{radius * std::cos(bearing), radius * std::sin(bearing),
                               wrap_angle(2.0 * kPi * h / options.start_headings)};
      const SolverResult candidate = solve_from(own, other, ranges_m, start, options);
      ++starts;
      if (candidate.final_cost < best.final_cost) {
        best = candidate;
      }
    }
  }
  best.starts = starts;
  return best;
}

}  // namespace robodds::uwb_relative_estimator
