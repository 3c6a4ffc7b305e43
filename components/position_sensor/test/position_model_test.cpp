#include "components/position_sensor/position_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace robodds::position_sensor {
namespace {

constexpr int kSamples = 100000;

/// Sample moments of the fix error (fix - truth) over many fixes of one pose.
struct ErrorMoments {
  double mean_x = 0.0;
  double mean_y = 0.0;
  double var_x = 0.0;
  double var_y = 0.0;
  double correlation_xy = 0.0;
};

ErrorMoments error_moments(const model::Pose2& truth, const PositionSensorParams& params,
                           RandomEngine& engine, int samples) {
  double sum_x = 0.0, sum_y = 0.0, sum_xx = 0.0, sum_yy = 0.0, sum_xy = 0.0;
  for (int i = 0; i < samples; ++i) {
    const PositionFix fix = measure_position(truth, params, engine);
    const double ex = fix.x - truth.x;
    const double ey = fix.y - truth.y;
    sum_x += ex;
    sum_y += ey;
    sum_xx += ex * ex;
    sum_yy += ey * ey;
    sum_xy += ex * ey;
  }
  ErrorMoments m;
  m.mean_x = sum_x / samples;
  m.mean_y = sum_y / samples;
  m.var_x = sum_xx / samples - m.mean_x * m.mean_x;
  m.var_y = sum_yy / samples - m.mean_y * m.mean_y;
  m.correlation_xy = (sum_xy / samples - m.mean_x * m.mean_y) / std::sqrt(m.var_x * m.var_y);
  return m;
}

TEST(PositionModel, NoiseHasZeroMeanConfiguredVarianceAndNoCorrelation) {
  PositionSensorParams params;
  params.noise_var_x_m2 = 2.28;
  params.noise_var_y_m2 = 0.5;  // different per axis: catches swapped axes
  RandomEngine engine(derive_seed(1, "position_sensor/statistics"));
  const model::Pose2 truth{3.0, -7.5, 1.2};
  const ErrorMoments m = error_moments(truth, params, engine, kSamples);

  // Tolerances: 5 standard errors. Mean: sigma/sqrt(n). Variance: var*sqrt(2/n).
  // Correlation: 1/sqrt(n).
  const double n = kSamples;
  EXPECT_NEAR(m.mean_x, 0.0, 5.0 * std::sqrt(params.noise_var_x_m2 / n));
  EXPECT_NEAR(m.mean_y, 0.0, 5.0 * std::sqrt(params.noise_var_y_m2 / n));
  EXPECT_NEAR(m.var_x, params.noise_var_x_m2, 5.0 * params.noise_var_x_m2 * std::sqrt(2.0 / n));
  EXPECT_NEAR(m.var_y, params.noise_var_y_m2, 5.0 * params.noise_var_y_m2 * std::sqrt(2.0 / n));
  EXPECT_NEAR(m.correlation_xy, 0.0, 5.0 / std::sqrt(n));
}

TEST(PositionModel, ClaimedVarianceIsTheConfiguredOne) {
  PositionSensorParams params;
  params.noise_var_x_m2 = 1.5;
  params.noise_var_y_m2 = 0.25;
  RandomEngine engine(5);
  const PositionFix fix = measure_position(model::Pose2{}, params, engine);
  EXPECT_EQ(fix.var_x, 1.5);
  EXPECT_EQ(fix.var_y, 0.25);
}

TEST(PositionModel, ZeroNoiseGivesExactTruth) {
  PositionSensorParams params;
  params.noise_var_x_m2 = 0.0;
  params.noise_var_y_m2 = 0.0;
  RandomEngine engine(derive_seed(2, "position_sensor/zero_noise"));
  const model::Pose2 truth{12.345, -0.001, -2.0};
  for (int i = 0; i < 1000; ++i) {
    const PositionFix fix = measure_position(truth, params, engine);
    ASSERT_EQ(fix.x, truth.x);
    ASSERT_EQ(fix.y, truth.y);
    ASSERT_EQ(fix.var_x, 0.0);
    ASSERT_EQ(fix.var_y, 0.0);
  }
}

TEST(PositionModel, SameSeedGivesIdenticalSequence) {
  const PositionSensorParams params;
  RandomEngine a(derive_seed(42, "position_sensor/robot1"));
  RandomEngine b(derive_seed(42, "position_sensor/robot1"));
  const model::Pose2 truth{1.0, 2.0, 0.3};
  for (int i = 0; i < 1000; ++i) {
    const PositionFix fa = measure_position(truth, params, a);
    const PositionFix fb = measure_position(truth, params, b);
    ASSERT_EQ(fa.x, fb.x);
    ASSERT_EQ(fa.y, fb.y);
  }
}

TEST(PositionModel, DifferentSeedGivesDifferentFixes) {
  const PositionSensorParams params;
  RandomEngine a(derive_seed(42, "position_sensor/robot1"));
  RandomEngine b(derive_seed(42, "position_sensor/robot2"));
  const model::Pose2 truth;
  const PositionFix fa = measure_position(truth, params, a);
  const PositionFix fb = measure_position(truth, params, b);
  EXPECT_NE(fa.x, fb.x);
  EXPECT_NE(fa.y, fb.y);
}

TEST(PositionModel, DrawsTwoNormalsPerFixWhateverTheVariance) {
  // The stream position must not depend on the configuration (see position_model.hpp).
  PositionSensorParams noisy;
  PositionSensorParams exact;
  exact.noise_var_x_m2 = 0.0;
  exact.noise_var_y_m2 = 0.0;
  RandomEngine a(9);
  RandomEngine b(9);
  measure_position(model::Pose2{}, noisy, a);
  measure_position(model::Pose2{}, exact, b);
  EXPECT_EQ(a, b);
}

TEST(PositionModel, OutliersHaveTheConfiguredRateAndOffsetAlongPlusX) {
  PositionSensorParams params;
  params.noise_var_x_m2 = 0.0;
  params.noise_var_y_m2 = 0.0;
  params.outlier_probability = 0.05;
  params.outlier_offset_m = 30.0;
  RandomEngine engine(derive_seed(3, "position_sensor/outliers"));
  const model::Pose2 truth{4.0, -2.0, 0.5};
  int outliers = 0;
  for (int i = 0; i < kSamples; ++i) {
    const PositionFix fix = measure_position(truth, params, engine);
    ASSERT_EQ(fix.y, truth.y);
    if (fix.x != truth.x) {
      ASSERT_EQ(fix.x, truth.x + 30.0);
      ++outliers;
    }
    ASSERT_EQ(fix.var_x, 0.0);  // an outlier does not announce itself
  }
  // Binomial: 5 standard errors.
  const double p = params.outlier_probability;
  EXPECT_NEAR(outliers / static_cast<double>(kSamples), p, 5.0 * std::sqrt(p * (1.0 - p) / kSamples));
}

TEST(PositionModel, WithoutOutliersTheStreamIsThatOfTheSensorWithoutTheFeature) {
  // outlier_probability 0 draws no uniform: old scenarios keep their exact outputs.
  PositionSensorParams off;
  off.outlier_offset_m = 100.0;
  RandomEngine a(9);
  RandomEngine b(9);
  measure_position(model::Pose2{}, off, a);
  standard_normal(b);
  standard_normal(b);
  EXPECT_EQ(a, b);
  PositionSensorParams on = off;
  on.outlier_probability = 0.5;
  measure_position(model::Pose2{}, on, a);
  standard_normal(b);
  standard_normal(b);
  EXPECT_NE(a, b);  // ... and with outliers on, one uniform more
}

}  // namespace
}  // namespace robodds::position_sensor
