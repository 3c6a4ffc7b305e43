#include "components/pf_estimator/likelihood.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace robodds::pf_estimator {
namespace {

ParticleSet particles_on_x_axis(Eigen::Index count, double spacing_m) {
  ParticleSet particles;
  particles.resize(count);
  for (Eigen::Index i = 0; i < count; ++i) {
    particles.x[i] = spacing_m * static_cast<double>(i);
  }
  particles.y.setZero();
  particles.theta.setZero();
  return particles;
}

TEST(PositionLogLikelihood, AddsTheExponentOfEquationFive) {
  ParticleSet particles = particles_on_x_axis(3, 1.0);
  particles.y << 0.0, 2.0, -1.0;
  Eigen::ArrayXd log_weights(3);
  log_weights << 0.0, -1.0, 0.5;
  const double s = 1.5;
  add_position_log_likelihood(particles, 0.5, 0.25, s, log_weights);
  const double two_var = 2.0 * s * s;
  EXPECT_NEAR(log_weights[0], 0.0 - (0.25 + 0.0625) / two_var, 1e-15);
  EXPECT_NEAR(log_weights[1], -1.0 - (0.25 + 3.0625) / two_var, 1e-15);
  EXPECT_NEAR(log_weights[2], 0.5 - (2.25 + 1.5625) / two_var, 1e-15);
}

TEST(NormalizeLogWeights, GivesWeightsProportionalToTheLikelihoodSummingToOne) {
  Eigen::ArrayXd log_weights(4);
  log_weights << -1.0, -2.0, -3.0, -1.0;
  Eigen::ArrayXd weights;
  ASSERT_TRUE(normalize_log_weights(log_weights, weights));
  EXPECT_NEAR(weights.sum(), 1.0, 1e-15);
  EXPECT_NEAR(weights[1] / weights[0], std::exp(-1.0), 1e-15);
  EXPECT_NEAR(weights[2] / weights[0], std::exp(-2.0), 1e-15);
  EXPECT_DOUBLE_EQ(weights[3], weights[0]);
  // log_weights now hold log(weights): normalising again changes nothing.
  EXPECT_NEAR((log_weights.exp() - weights).abs().maxCoeff(), 0.0, 1e-15);
}

TEST(NormalizeLogWeights, DoesNotUnderflowFarFromTheCloud) {
  // A fix 1 km away: every linear likelihood is exp(-2e5) = 0 in double precision.
  const ParticleSet particles = particles_on_x_axis(100, 0.01);
  Eigen::ArrayXd log_weights = Eigen::ArrayXd::Zero(100);
  add_position_log_likelihood(particles, -1000.0, 0.0, std::sqrt(2.28), log_weights);
  ASSERT_EQ(std::exp(log_weights.maxCoeff()), 0.0);  // what a linear-space filter would see
  Eigen::ArrayXd weights;
  ASSERT_TRUE(normalize_log_weights(log_weights, weights));
  EXPECT_TRUE(weights.isFinite().all());
  EXPECT_NEAR(weights.sum(), 1.0, 1e-12);
  // The nearest particle dominates, and weights decrease with distance.
  Eigen::Index best = -1;
  weights.maxCoeff(&best);
  EXPECT_EQ(best, 0);
  for (Eigen::Index i = 1; i < 100; ++i) {
    EXPECT_LE(weights[i], weights[i - 1]);
  }
}

TEST(NormalizeLogWeights, ZeroWeightsStayExactlyZero) {
  // -inf and very negative log-weights must give 0, not the ~5.6e-309 Eigen's exp() returns.
  Eigen::ArrayXd log_weights(4);
  log_weights << 0.0, -std::numeric_limits<double>::infinity(), -1000.0, -1.0;
  Eigen::ArrayXd weights;
  ASSERT_TRUE(normalize_log_weights(log_weights, weights));
  EXPECT_EQ(weights[1], 0.0);
  EXPECT_EQ(weights[2], 0.0);
  EXPECT_NEAR(weights[0] + weights[3], 1.0, 1e-15);
}

TEST(NormalizeLogWeights, ReportsDegenerateWeights) {
  Eigen::ArrayXd weights;
  Eigen::ArrayXd all_minus_inf =
      Eigen::ArrayXd::Constant(5, -std::numeric_limits<double>::infinity());
  EXPECT_FALSE(normalize_log_weights(all_minus_inf, weights));
  Eigen::ArrayXd empty;
  EXPECT_FALSE(normalize_log_weights(empty, weights));
}

}  // namespace
}  // namespace robodds::pf_estimator
