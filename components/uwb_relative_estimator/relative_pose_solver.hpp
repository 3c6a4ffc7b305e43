#pragma once
// Single-epoch relative pose from UWB array ranges (paper 3, eq. 1): the pose x = (x, y, theta) of
// robot j in robot i's frame that minimises sum over node pairs (k, l) of
// rho((r_kl - d(x, C_i^k, C_j^l))^2), solved by Levenberg-Marquardt (plain least squares: its own, with
// Ceres' rules; a robust loss: Ceres). rho is a robust loss
// (an extension: the paper uses plain least squares, which non-line-of-sight outliers bias).

#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "common/param_table.hpp"
#include "components/uwb_relative_estimator/relative_pose.hpp"
#include "common/model/uwb_array.hpp"

namespace robodds::uwb_relative_estimator {

// The arrays are shared with the UWB sensor (common/model/uwb_array.hpp); these names keep
// uwb_relative_estimator::UwbArray and uwb_relative_estimator::square_array working.
using model::square_array;
using model::UwbArray;

enum class RobustLoss {
  kNone,    // plain least squares, as the paper
  kHuber,   // quadratic below loss_scale_m, linear above
  kSoftL1,  // smooth version of the same
};

/// "none" / "huber" / "soft_l1"; throws std::invalid_argument("loss: ...") otherwise.
RobustLoss robust_loss_from_string(std::string_view text);
std::string to_string(RobustLoss loss);

// Units, ranges and one-line descriptions of these fields: solver_param_table() in
// relative_pose_solver.cpp (the one source; its doc() prints them). Defaults: the member
// initialisers.
struct SolverOptions {
  RobustLoss loss = RobustLoss::kHuber;
  double loss_scale_m = 0.15;
  /// Only without an initial pose: start_directions x start_headings starts (8 x 4 = 32); the
  /// lowest cost wins.
  int start_directions = 8;
  int start_headings = 4;
  int max_iterations = 50;

  /// Throws std::invalid_argument "key: requirement (got value)".
  void validate() const;
};

/// Keys, units, ranges and descriptions of SolverOptions (defaults: the initialisers above).
const params::ParamTable<SolverOptions>& solver_param_table();

struct SolverResult {
  model::Pose2 pose;
  double final_cost = 0.0;  // Ceres cost, 1/2 sum of rho(residual^2), m^2
  int starts = 0;           // how many starts were solved
  bool converged = false;   // the winning start reported convergence
};

/// Throws std::invalid_argument naming the caller and the problem: an empty array, a matrix that is
/// not own.size() x other.size(), or a range (k, l) that is negative or not finite. The one check of
/// a UWB range matrix (the solver, the tracker and the particle filters call it).
void require_valid_ranges(const char* caller, const UwbArray& own, const UwbArray& other, const Eigen::MatrixXd& ranges_m);

/// Solves eq. (1) for the K x L matrix `ranges_m` (row k: node k of `own`, column l: node l of
/// `other`). With `initial` (e.g. the previous epoch's pose) one start from there; without it the
/// multi-start of SolverOptions. Throws std::invalid_argument if the matrix does not match the
/// arrays or holds a non-finite or negative range (the message names the pair).
SolverResult solve_relative_pose(const UwbArray& own, const UwbArray& other, const Eigen::MatrixXd& ranges_m,
                                 const std::optional<model::Pose2>& initial, const SolverOptions& options);

}  // namespace robodds::uwb_relative_estimator
