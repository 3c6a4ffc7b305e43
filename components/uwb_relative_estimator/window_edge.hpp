#pragma once
// One edge of paper 3's sliding-window pose graph (eq. 2) as a Ceres cost function with analytic
// Jacobians. Internal to SlidingWindowGraph; a header of its own so that its test can compare it
// with Ceres' autodiff.

#include <ceres/sized_cost_function.h>

#include "common/model/pose2.hpp"

namespace robodds::uwb_relative_estimator {

/// Residual of one edge "pose b seen from pose a is `measured`", each row divided by its std:
/// between(a, b) - measured, the heading difference wrapped. Poses are (x m, y m, theta rad) in the
/// window's frame.
///
/// The Jacobians are analytic: at w = 160 the window has ~960 edges and autodiff's 6-wide Jets
/// were a fifth of the solve (docs/performance.md, "Paper 3"). Every value and derivative is
/// computed with the operations, in the order, that ceres::Jet applied to the templated form
/// (a_b = R(theta_a)^T (p_b - p_a); atan2(sin, cos) for the wrap; a product with 1 / std), so the
/// solver sees bit-identical numbers and lockstep outputs did not change
/// (test/window_edge_test.cpp).
class WindowEdge {
 public:
  /// measured: pose b in frame a; the stds are > 0 (SlidingWindowGraph validates them).
  WindowEdge(const model::Pose2& measured, double xy_std_m, double theta_std_rad);

  /// As ceres::CostFunction::Evaluate: parameters {a, b}, 3 residuals, jacobians null or {3 x 3
  /// row-major for a or null, for b or null}.
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const;

 private:
  model::Pose2 measured_;
  double xy_std_m_;
  double theta_std_rad_;
  double xy_std_inverse_;
  double theta_std_inverse_;
};

/// WindowEdge as a Ceres cost function (SlidingWindowGraph evaluates WindowEdge itself, with no
/// cost function to allocate per edge and solve; the tests solve the same edges with Ceres).
class WindowEdgeResidual final : public ceres::SizedCostFunction<3, 3, 3> {
 public:
  WindowEdgeResidual(const model::Pose2& measured, double xy_std_m, double theta_std_rad)
      : edge_(measured, xy_std_m, theta_std_rad) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    return edge_.Evaluate(parameters, residuals, jacobians);
  }

 private:
  WindowEdge edge_;
};

}  // namespace robodds::uwb_relative_estimator
