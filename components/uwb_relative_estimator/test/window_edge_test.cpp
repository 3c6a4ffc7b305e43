#include "components/uwb_relative_estimator/window_edge.hpp"

#include <gtest/gtest.h>

#include <ceres/autodiff_cost_function.h>

#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>

#include "common/angle.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

/// The edge as it was written for autodiff before the analytic Jacobians (the reference the
/// analytic form must reproduce bit for bit, so that lockstep outputs stay byte-identical).
struct AutodiffEdge {
  model::Pose2 measured;
  double xy_std_m;
  double theta_std_rad;

  template <class T>
  bool operator()(const T* const a, const T* const b, T* residual) const {
    using std::atan2;
    using std::cos;
    using std::sin;
    T a_b[3];
    model::between_unwrapped(a, b, a_b);
    const T dtheta = a_b[2] - T(measured.theta);
    residual[0] = (a_b[0] - T(measured.x)) / T(xy_std_m);
    residual[1] = (a_b[1] - T(measured.y)) / T(xy_std_m);
    residual[2] = atan2(sin(dtheta), cos(dtheta)) / T(theta_std_rad);
    return true;
  }
};

struct Evaluation {
  std::array<double, 3> residual{};
  std::array<double, 9> jacobian_a{};
  std::array<double, 9> jacobian_b{};
};

/// Evaluates `cost` at (a, b); `with_jacobians` false takes Ceres' residual-only path; `only_b`
/// asks for b's Jacobian only (a's block is constant, as the window's gauge pose).
Evaluation evaluate(const ceres::CostFunction& cost, const std::array<double, 3>& a, const std::array<double, 3>& b,
                    bool with_jacobians, bool only_b = false) {
  Evaluation e;
  const double* parameters[2] = {a.data(), b.data()};
  double* jacobians[2] = {only_b ? nullptr : e.jacobian_a.data(), e.jacobian_b.data()};
  EXPECT_TRUE(cost.Evaluate(parameters, e.residual.data(), with_jacobians ? jacobians : nullptr));
  return e;
}

bool same_bits(const Evaluation& x, const Evaluation& y) {
  return std::memcmp(&x, &y, sizeof(Evaluation)) == 0;
}

TEST(WindowEdgeResidual, MatchesAutodiffBitForBitOnEveryPath) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> position(-20.0, 20.0);
  std::uniform_real_distribution<double> angle(-4.0, 4.0);  // beyond +-pi: the window holds unwrapped headings
  std::uniform_real_distribution<double> std_m(0.003, 0.5);
  int mismatches = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const model::Pose2 measured{position(random), position(random), wrap_angle(angle(random))};
    const double xy_std = std_m(random);
    const double theta_std = std_m(random);
    const WindowEdgeResidual analytic(measured, xy_std, theta_std);
    const ceres::AutoDiffCostFunction<AutodiffEdge, 3, 3, 3> reference(new AutodiffEdge{measured, xy_std, theta_std});
    const std::array<double, 3> a{position(random), position(random), angle(random)};
    std::array<double, 3> b{position(random), position(random), angle(random)};
    if (trial % 4 == 0) {
      b[2] = a[2] + measured.theta + kPi;  // the heading residual at the wrap
    }
    for (const bool with_jacobians : {false, true}) {
      for (const bool only_b : {false, true}) {
        if (!same_bits(evaluate(analytic, a, b, with_jacobians, only_b), evaluate(reference, a, b, with_jacobians, only_b))) {
          ++mismatches;
        }
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(WindowEdgeResidual, JacobianMatchesCentralDifferences) {
  const model::Pose2 measured{1.0, -2.0, 0.4};
  const WindowEdgeResidual edge(measured, 0.05, 0.1);
  const std::array<double, 3> a{0.5, 1.5, 2.9};
  const std::array<double, 3> b{3.0, -1.0, -2.8};
  const Evaluation at = evaluate(edge, a, b, true);
  const double h = 1e-6;
  for (int block = 0; block < 2; ++block) {
    for (int k = 0; k < 3; ++k) {
      std::array<double, 3> plus_a = a, minus_a = a, plus_b = b, minus_b = b;
      (block == 0 ? plus_a : plus_b)[k] += h;
      (block == 0 ? minus_a : minus_b)[k] -= h;
      const Evaluation plus = evaluate(edge, plus_a, plus_b, false);
      const Evaluation minus = evaluate(edge, minus_a, minus_b, false);
      for (int row = 0; row < 3; ++row) {
        const double numeric = (plus.residual[row] - minus.residual[row]) / (2.0 * h);
        const double analytic = (block == 0 ? at.jacobian_a : at.jacobian_b)[row * 3 + k];
        EXPECT_NEAR(analytic, numeric, 1e-4 * std::max(1.0, std::abs(numeric))) << "block " << block << " row " << row << " col " << k;
      }
    }
  }
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator
