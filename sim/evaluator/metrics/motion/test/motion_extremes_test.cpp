#include "sim/evaluator/metrics/motion/motion_extremes.hpp"

#include <gtest/gtest.h>

namespace robodds::evaluator {
namespace {

TEST(MotionExtremes, SpeedsWheelSpeedsAndAccelerationsFromConsecutiveSamples) {
  MotionExtremesTracker t(0.01, 0.3);
  EXPECT_FALSE(t.seen());
  t.add({0, 0.0, 0.0});
  t.add({1, 0.01, -0.05});   // 1 m/s^2, 5 rad/s^2
  t.add({3, 0.05, -0.05});   // two steps later: 0.04 m/s over 0.02 s = 2 m/s^2
  t.add({4, -1.0, 2.0});     // wheels -1.3 and -0.7; 105 m/s^2, 205 rad/s^2
  ASSERT_TRUE(t.seen());
  const MotionExtremes& e = t.extremes();
  EXPECT_EQ(e.samples, 4u);
  EXPECT_DOUBLE_EQ(e.max_abs_v_mps, 1.0);
  EXPECT_DOUBLE_EQ(e.max_abs_omega_radps, 2.0);
  EXPECT_NEAR(e.max_abs_wheel_speed_mps, 1.3, 1e-12);
  EXPECT_NEAR(e.max_abs_accel_mps2, 105.0, 1e-9);
  EXPECT_NEAR(e.max_abs_angular_accel_radps2, 205.0, 1e-9);
}

TEST(MotionExtremes, TheTimeBetweenSamplesIsTheirStepDifference) {
  MotionExtremesTracker t(0.01, 0.5);
  t.add({0, 0.0, 0.0});
  t.add({10, 1.0, 0.0});  // a 10 Hz stream: 1 m/s over 0.1 s
  EXPECT_NEAR(t.extremes().max_abs_accel_mps2, 10.0, 1e-9);
  t.add({10, 5.0, 0.0});  // a second sample at the same step: no division by zero
  EXPECT_NEAR(t.extremes().max_abs_accel_mps2, 10.0, 1e-9);
  EXPECT_DOUBLE_EQ(t.extremes().max_abs_v_mps, 5.0);
}

}  // namespace
}  // namespace robodds::evaluator
