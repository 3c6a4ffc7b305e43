#include "components/odometry_sensor/twist_accumulator.hpp"

#include <gtest/gtest.h>

namespace robodds::odometry_sensor {
namespace {

TEST(TwistAccumulator, EmptyGivesZeroTwist) {
  const TwistAccumulator acc;
  EXPECT_EQ(acc.mean().v, 0.0);
  EXPECT_EQ(acc.mean().omega, 0.0);
  EXPECT_EQ(acc.elapsed_s(), 0.0);
}

TEST(TwistAccumulator, MeanIsDistanceOverCoveredTime) {
  TwistAccumulator acc;
  acc.add(model::Twist{1.0, 0.2}, 0.01);
  acc.add(model::Twist{3.0, -0.4}, 0.01);
  EXPECT_DOUBLE_EQ(acc.elapsed_s(), 0.02);
  EXPECT_DOUBLE_EQ(acc.mean().v, 2.0);
  EXPECT_NEAR(acc.mean().omega, -0.1, 1e-15);
}

TEST(TwistAccumulator, ConstantTwistIsReproducedWhateverTheNumberOfSteps) {
  // The real-time bug this guards against: two 10 ms states in a 20 ms period must not double v.
  for (int steps : {1, 2, 3, 7}) {
    TwistAccumulator acc;
    for (int i = 0; i < steps; ++i) {
      acc.add(model::Twist{5.0, 1.5}, 0.01);
    }
    EXPECT_DOUBLE_EQ(acc.mean().v, 5.0) << steps;
    EXPECT_DOUBLE_EQ(acc.mean().omega, 1.5) << steps;
  }
}

TEST(TwistAccumulator, ResetStartsAFreshPeriod) {
  TwistAccumulator acc;
  acc.add(model::Twist{9.0, 9.0}, 0.5);
  acc.reset();
  acc.add(model::Twist{1.0, -1.0}, 0.01);
  EXPECT_DOUBLE_EQ(acc.mean().v, 1.0);
  EXPECT_DOUBLE_EQ(acc.mean().omega, -1.0);
  EXPECT_DOUBLE_EQ(acc.elapsed_s(), 0.01);
}

}  // namespace
}  // namespace robodds::odometry_sensor
