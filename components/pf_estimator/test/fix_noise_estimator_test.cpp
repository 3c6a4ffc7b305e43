#include "components/pf_estimator/fix_noise_estimator.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/random.hpp"

namespace robodds::pf_estimator {
namespace {

// Innovations of a filter whose cloud has variance p per axis, fixes of std sigma per axis.
void feed(FixNoiseEstimator& estimator, double sigma_m, double cloud_variance_m2, int fixes, RandomEngine& engine,
          double outlier_share = 0.0, double outlier_m = 0.0) {
  const double std_m = std::sqrt(sigma_m * sigma_m + cloud_variance_m2);
  for (int i = 0; i < fixes; ++i) {
    const double jump = uniform01(engine) < outlier_share ? outlier_m : 0.0;
    estimator.add(std_m * standard_normal(engine) + jump, std_m * standard_normal(engine), cloud_variance_m2);
  }
}

TEST(FixNoiseEstimator, StaysAtTheFloorUntilEnoughFixes) {
  FixNoiseEstimator estimator(1.5, 300);
  RandomEngine engine(1);
  feed(estimator, 10.0, 0.0, static_cast<int>(FixNoiseEstimator::kMinFixes) - 1, engine);
  EXPECT_DOUBLE_EQ(estimator.std_m(), 1.5);
  feed(estimator, 10.0, 0.0, 1, engine);
  EXPECT_GT(estimator.std_m(), 5.0);
}

TEST(FixNoiseEstimator, FindsTheNoiseOfFixesNoisierThanConfiguredNetOfTheCloudSpread) {
  for (const double cloud_variance : {0.0, 0.2, 4.0}) {
    FixNoiseEstimator estimator(1.51, 300);
    RandomEngine engine(2);
    feed(estimator, 4.53, cloud_variance, 300, engine);
    EXPECT_NEAR(estimator.std_m(), 4.53, 0.1 * 4.53) << cloud_variance;
  }
}

TEST(FixNoiseEstimator, NeverGoesBelowTheFloor) {
  FixNoiseEstimator estimator(1.51, 300);
  RandomEngine engine(3);
  feed(estimator, 0.5, 0.1, 300, engine);
  EXPECT_DOUBLE_EQ(estimator.std_m(), 1.51);
}

TEST(FixNoiseEstimator, TenPercentGrossOutliersHardlyMoveIt) {
  FixNoiseEstimator estimator(1.0, 300);
  RandomEngine engine(4);
  feed(estimator, 3.0, 0.1, 600, engine, 0.1, 50.0);
  // The median moves to the 0.56 quantile: the variance by ~1.2x (std ~1.1x), plus sampling noise.
  EXPECT_NEAR(estimator.std_m(), 3.0, 0.2 * 3.0);
}

TEST(FixNoiseEstimator, FollowsAChangeWithinItsWindow) {
  FixNoiseEstimator estimator(1.0, 100);
  RandomEngine engine(5);
  feed(estimator, 4.0, 0.0, 100, engine);
  feed(estimator, 1.0, 0.0, 100, engine);
  EXPECT_LT(estimator.std_m(), 1.3);
}

TEST(FixNoiseEstimator, WindowZeroAssumesTheFloor) {
  FixNoiseEstimator estimator(1.51, 0);
  RandomEngine engine(6);
  feed(estimator, 5.0, 0.0, 100, engine);
  EXPECT_DOUBLE_EQ(estimator.std_m(), 1.51);
  EXPECT_EQ(estimator.samples(), 0u);
}

}  // namespace
}  // namespace robodds::pf_estimator
