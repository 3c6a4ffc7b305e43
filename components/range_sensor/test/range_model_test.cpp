#include "components/range_sensor/range_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace robodds::range_sensor {
namespace {

TEST(RangeModel, TrueRangeIsTheEuclideanDistance) {
  EXPECT_DOUBLE_EQ(true_range(3.0, 4.0, 0.0, 0.0), 5.0);
  EXPECT_DOUBLE_EQ(true_range(1000.0, 1000.0, 1000.0, 1000.0), 0.0);
}

TEST(RangeModel, NoiseHasTheConfiguredSigmaAndNoBias) {
  RangeSensorParams p;
  p.noise_sigma_m = 0.5;
  RandomEngine engine(42);
  double sum = 0.0;
  double sum_sq = 0.0;
  constexpr int kN = 20000;
  for (int i = 0; i < kN; ++i) {
    const double e = measure_range(200.0, p, engine) - 200.0;
    sum += e;
    sum_sq += e * e;
  }
  const double mean = sum / kN;
  const double sigma = std::sqrt(sum_sq / kN - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4 * 0.5 / std::sqrt(kN));  // 4 standard errors
  EXPECT_NEAR(sigma, 0.5, 0.02);
}

TEST(RangeModel, NoiseFreeIsExactAndNearZeroIsClampedAtZero) {
  RangeSensorParams p;
  p.noise_sigma_m = 0.0;
  RandomEngine engine(1);
  EXPECT_DOUBLE_EQ(measure_range(123.25, p, engine), 123.25);
  p.noise_sigma_m = 1.0;
  for (int i = 0; i < 1000; ++i) {
    EXPECT_GE(measure_range(0.1, p, engine), 0.0);
  }
}

TEST(RangeModel, DropoutsHappenAtTheConfiguredRate) {
  RangeSensorParams p;
  p.dropout_probability = 0.2;
  RandomEngine engine(7);
  int lost = 0;
  constexpr int kN = 20000;
  for (int i = 0; i < kN; ++i) {
    lost += sample_lost(p, engine) ? 1 : 0;
  }
  EXPECT_NEAR(static_cast<double>(lost) / kN, 0.2, 0.015);
  p.dropout_probability = 0.0;
  for (int i = 0; i < 1000; ++i) {
    EXPECT_FALSE(sample_lost(p, engine));
  }
}

}  // namespace
}  // namespace robodds::range_sensor
