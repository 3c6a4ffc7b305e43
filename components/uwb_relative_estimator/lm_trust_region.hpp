#pragma once
// The trust region of Ceres' Levenberg-Marquardt (LevenbergMarquardtStrategy with
// TrustRegionMinimizer's defaults), shared by this component's own solvers that replaced a
// ceres::Problem (issue 29): the sliding window (eq. 2), the tc window and eq. (1). Each solver
// keeps its own linear algebra and stopping tests; the radius, its growth and shrinking, the
// damping of the normal equations and the step acceptance are this one class.

#include <algorithm>
#include <cmath>

namespace robodds::uwb_relative_estimator {

class LmTrustRegion {
 public:
  /// A step whose actual over predicted cost decrease is at most this is rejected (Ceres'
  /// min_relative_decrease).
  static constexpr double kMinRelativeDecrease = 1e-3;

  /// `initial_radius`: Ceres' initial_trust_region_radius (its default 1e4; 1e6 for a warm start,
  /// whose first step is then nearly Gauss-Newton's).
  explicit LmTrustRegion(double initial_radius) : radius_(initial_radius) {}

  /// What the damped normal equations add to a (scaled) diagonal entry `diagonal` of J^T J:
  /// diagonal / radius, the entry clamped to [1e-6, 1e32] (Ceres' min/max_lm_diagonal).
  double damping(double diagonal) const { return std::min(std::max(diagonal, 1e-6), 1e32) / radius_; }

  /// Whether a step is taken: its cost finite, a decrease predicted (`model_change` > 0), and the
  /// actual decrease over the predicted one (`relative_decrease`) above kMinRelativeDecrease.
  static bool accepts(double relative_decrease, double model_change, double candidate_cost) {
    return std::isfinite(candidate_cost) && model_change > 0.0 && relative_decrease > kMinRelativeDecrease;
  }

  /// After an accepted step of ratio `relative_decrease` (actual / predicted decrease): the radius
  /// grows by up to 3x, at most to 1e16, and the next rejection shrinks it by 2 again.
  void step_accepted(double relative_decrease) {
    radius_ = std::min(1e16, radius_ / std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * relative_decrease - 1.0, 3)));
    decrease_factor_ = 2.0;
  }

  /// After a rejected or invalid step: the radius shrinks, by 2, 4, 8, ... for rejections in a row.
  /// True once it is below 1e-32 (Ceres' min_trust_region_radius: the solve ends, converged).
  bool step_rejected() {
    radius_ /= decrease_factor_;
    decrease_factor_ *= 2.0;
    return radius_ < 1e-32;
  }

  double radius() const { return radius_; }

 private:
  double radius_;
  double decrease_factor_ = 2.0;
};

}  // namespace robodds::uwb_relative_estimator
