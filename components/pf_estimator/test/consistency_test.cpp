#include "components/pf_estimator/consistency.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "common/random.hpp"

namespace robodds::pf_estimator {
namespace {

ParticleSet cloud_around(double x, double y, double std_m, Eigen::Index count, RandomEngine& engine) {
  ParticleSet particles;
  particles.resize(count);
  for (Eigen::Index i = 0; i < count; ++i) {
    particles.x[i] = x + std_m * standard_normal(engine);
    particles.y[i] = y + std_m * standard_normal(engine);
    particles.theta[i] = 0.0;
  }
  return particles;
}

TEST(PositionFixNis, PointCloudGivesTheSquaredDistanceOverTheMeasurementVariance) {
  ParticleSet particles;
  particles.resize(2);
  particles.x << 1.0, 1.0;
  particles.y << 2.0, 2.0;
  particles.theta.setZero();
  const Eigen::ArrayXd w = Eigen::ArrayXd::Constant(2, 0.5);
  // e = (3, 4), S = 4 I: d^2 = 25 / 4.
  EXPECT_NEAR(position_fix_nis(particles, w, 4.0, 6.0, 2.0), 25.0 / 4.0, 1e-12);
}

TEST(PositionFixNis, UsesTheWeightedMeanAndTheCloudCovariance) {
  ParticleSet particles;
  particles.resize(2);
  particles.x << -1.0, 1.0;  // spread along x only: P = diag(1, 0) with equal weights
  particles.y << 0.0, 0.0;
  particles.theta.setZero();
  const Eigen::ArrayXd w = Eigen::ArrayXd::Constant(2, 0.5);
  // Along x, S = 1 + 1 = 2; along y, S = 1.
  EXPECT_NEAR(position_fix_nis(particles, w, 2.0, 0.0, 1.0), 4.0 / 2.0, 1e-12);
  EXPECT_NEAR(position_fix_nis(particles, w, 0.0, 2.0, 1.0), 4.0, 1e-12);
  // The weighted mean, not the plain one: all weight on x = 1.
  Eigen::ArrayXd one_hot(2);
  one_hot << 0.0, 1.0;
  EXPECT_NEAR(position_fix_nis(particles, one_hot, 3.0, 0.0, 1.0), 4.0, 1e-12);
}

TEST(PositionFixNis, ConsistentFixesAverageTwoAndPassTheGateAtItsRate) {
  RandomEngine engine(derive_seed(1, "consistency/chi2"));
  const ParticleSet particles = cloud_around(5.0, -3.0, 0.5, 2000, engine);
  const Eigen::ArrayXd w = Eigen::ArrayXd::Constant(2000, 1.0 / 2000.0);
  // Fix noise 1.5 m, cloud 0.5 m: the fix's total spread per axis is sqrt(0.25 + 2.25).
  const double total_std = std::sqrt(0.25 + 2.25);
  const double gate = chi_square_2dof_quantile(0.99);
  const int n = 20000;
  double sum = 0.0;
  int outside = 0;
  for (int i = 0; i < n; ++i) {
    const double d2 = position_fix_nis(particles, w, 5.0 + total_std * standard_normal(engine),
                                       -3.0 + total_std * standard_normal(engine), 1.5);
    sum += d2;
    outside += d2 > gate ? 1 : 0;
  }
  // Chi-square 2 dof: mean 2, std 2; the cloud's sample covariance differs from 0.25 by ~3 %.
  EXPECT_NEAR(sum / n, 2.0, 0.1);
  EXPECT_NEAR(outside / static_cast<double>(n), 0.01, 5.0 * std::sqrt(0.01 * 0.99 / n) + 0.002);
}

TEST(ChiSquare2Dof, QuantilesAreMinusTwoLogTail) {
  EXPECT_NEAR(chi_square_2dof_quantile(0.99), 9.2103, 1e-4);
  EXPECT_NEAR(chi_square_2dof_quantile(0.95), 5.9915, 1e-4);
  EXPECT_EQ(chi_square_2dof_quantile(0.0), 0.0);
}

TEST(InconsistencyMonitor, ARunOfRejectedFixesMakesTheFilterLostAfterNineFixes) {
  InconsistencyMonitor monitor(10.0, 0.6, 5.0);
  int fixes = 0;
  while (!monitor.add(100.0, true)) {
    ++fixes;
    ASSERT_LT(fixes, 100);
  }
  // Share 1 - 0.9^n > 0.6 first at n = 9.
  EXPECT_EQ(fixes + 1, 9);
  EXPECT_EQ(monitor.mean_nis(), 2.0) << "rejected fixes do not enter the d^2 average";
  monitor.reset();
  EXPECT_EQ(monitor.rejected_share(), 0.0);
  EXPECT_EQ(monitor.mean_nis(), 2.0);
}

TEST(InconsistencyMonitor, AcceptedButLargeInnovationsMakeTheFilterLost) {
  // A drift inside the gate: every fix accepted with d^2 = 8.
  InconsistencyMonitor monitor(10.0, 0.6, 5.0);
  int fixes = 1;
  while (!monitor.add(8.0, false)) {
    ++fixes;
    ASSERT_LT(fixes, 100);
  }
  // 8 - 6 * 0.9^n > 5 first at n = 7.
  EXPECT_EQ(fixes, 7);
  EXPECT_EQ(monitor.rejected_share(), 0.0);
}

TEST(InconsistencyMonitor, FivePercentOutliersNeverLookLost) {
  // Consistent fixes (d^2 exponential with mean 2, the chi-square with 2 dof) and 5 % gross
  // outliers over 100000 fixes (~3 h at 10 Hz): with the filter's defaults, never lost.
  RandomEngine engine(derive_seed(2, "consistency/outliers"));
  const double gate = chi_square_2dof_quantile(0.99);
  InconsistencyMonitor monitor(10.0, 0.6, 5.0);
  double peak_share = 0.0;
  double peak_nis = 0.0;
  int lost = 0;
  for (int i = 0; i < 100000; ++i) {
    const double nis = uniform01(engine) < 0.05 ? 1e4 : -2.0 * std::log1p(-uniform01(engine));
    lost += monitor.add(nis, nis > gate) ? 1 : 0;
    peak_share = std::max(peak_share, monitor.rejected_share());
    peak_nis = std::max(peak_nis, monitor.mean_nis());
  }
  RecordProperty("peak_rejected_share", std::to_string(peak_share));
  RecordProperty("peak_mean_nis", std::to_string(peak_nis));
  EXPECT_EQ(lost, 0) << "peak share " << peak_share << ", peak mean d^2 " << peak_nis;
}

TEST(InconsistencyMonitor, FixesOnOneSideTripTheBiasCriterionButWhiteInnovationsDoNot) {
  // A steady 1.2 m offset along x with S = 2.4 I: each d^2 is only 0.6, far inside the gate and
  // below the mean-d^2 threshold, but the side never changes.
  FixInnovation offset;
  offset.ex = 1.2;
  offset.sxx = 2.4;
  offset.syy = 2.4;
  InconsistencyMonitor monitor(10.0, 0.6, 5.0, 50.0, 40.0);
  int fixes = 1;
  while (!monitor.add(offset, false)) {
    ++fixes;
    ASSERT_LT(fixes, 1000);
    EXPECT_LT(monitor.mean_nis(), 5.0);
  }
  // b^2 = 99 * 0.6 * (1 - 0.98^n)^2 > 40 first at n = 86 (8.6 s at 10 Hz).
  EXPECT_EQ(fixes, 86);
  InconsistencyMonitor off(10.0, 0.6, 5.0, 50.0, 0.0);
  for (int k = 0; k < 1000; ++k) {
    ASSERT_FALSE(off.add(offset, false)) << "the bias criterion is off at 0";
  }
  // White innovations with the claimed S, gated as the filter does: b^2 is ~chi-square(2) at
  // every fix, P(> 40) ~ 2e-9.
  const double gate = chi_square_2dof_quantile(0.99);
  RandomEngine engine(derive_seed(3, "consistency/bias"));
  InconsistencyMonitor white(10.0, 0.6, 5.0, 50.0, 40.0);
  double peak = 0.0;
  for (int k = 0; k < 100000; ++k) {
    FixInnovation f;
    f.sxx = 2.4;
    f.syy = 2.4;
    f.ex = std::sqrt(2.4) * standard_normal(engine);
    f.ey = std::sqrt(2.4) * standard_normal(engine);
    ASSERT_FALSE(white.add(f, f.nis() > gate)) << "fix " << k << ", b^2 " << white.bias_nis() << ", mean d^2 " << white.mean_nis();
    peak = std::max(peak, white.bias_nis());
  }
  RecordProperty("white_peak_bias_nis", std::to_string(peak));
  monitor.reset();
  EXPECT_EQ(monitor.bias_nis(), 0.0);
}

TEST(PositionFixInnovation, CarriesTheInnovationAndItsCovariance) {
  ParticleSet particles;
  particles.resize(2);
  particles.x << -1.0, 1.0;
  particles.y << 0.0, 0.0;
  particles.theta.setZero();
  const Eigen::ArrayXd w = Eigen::ArrayXd::Constant(2, 0.5);
  const FixInnovation f = position_fix_innovation(particles, w, 2.0, -1.0, 1.0);
  EXPECT_DOUBLE_EQ(f.ex, 2.0);
  EXPECT_DOUBLE_EQ(f.ey, -1.0);
  EXPECT_DOUBLE_EQ(f.sxx, 2.0);
  EXPECT_DOUBLE_EQ(f.syy, 1.0);
  EXPECT_DOUBLE_EQ(f.sxy, 0.0);
  EXPECT_DOUBLE_EQ(f.nis(), 4.0 / 2.0 + 1.0);
}

}  // namespace
}  // namespace robodds::pf_estimator
