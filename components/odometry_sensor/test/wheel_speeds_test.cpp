#include "components/odometry_sensor/wheel_speeds.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace robodds::odometry_sensor {
namespace {

TEST(WheelSpeeds, StraightMotionDrivesBothWheelsEqually) {
  const WheelSpeeds wheels = wheel_speeds_from_twist(model::Twist{1.5, 0.0}, 0.5);
  EXPECT_EQ(wheels.left, 1.5);
  EXPECT_EQ(wheels.right, 1.5);
}

TEST(WheelSpeeds, CounterClockwiseTurnSpeedsUpTheRightWheel) {
  // Turning in place at +2 rad/s with D = 0.5 m: rims move at -/+ omega D/2 = 0.5 m/s.
  const WheelSpeeds wheels = wheel_speeds_from_twist(model::Twist{0.0, 2.0}, 0.5);
  EXPECT_DOUBLE_EQ(wheels.left, -0.5);
  EXPECT_DOUBLE_EQ(wheels.right, 0.5);
}

TEST(WheelSpeeds, RoundTripTwistToWheelsToTwist) {
  for (double wheel_base_m : {0.1, 0.5, 2.0}) {
    for (double v : {-3.0, -0.2, 0.0, 0.7, 18.0}) {
      for (double omega : {-70.7, -1.0, 0.0, 0.013, 2.5}) {
        const WheelSpeeds wheels = wheel_speeds_from_twist(model::Twist{v, omega}, wheel_base_m);
        const model::Twist back =
            model::twist_from_wheel_speeds(wheels.left, wheels.right, wheel_base_m);
        // Rounding only: a few ulps of the largest rim speed involved.
        const double scale = std::abs(v) + std::abs(omega) * wheel_base_m;
        EXPECT_NEAR(back.v, v, 1e-14 * scale) << v << " " << omega << " " << wheel_base_m;
        EXPECT_NEAR(back.omega, omega, 1e-14 * scale / wheel_base_m)
            << v << " " << omega << " " << wheel_base_m;
      }
    }
  }
}

TEST(WheelSpeeds, RoundTripWheelsToTwistToWheels) {
  const double wheel_base_m = 0.5;
  const model::Twist twist = model::twist_from_wheel_speeds(0.3, 1.1, wheel_base_m);
  const WheelSpeeds wheels = wheel_speeds_from_twist(twist, wheel_base_m);
  EXPECT_NEAR(wheels.left, 0.3, 1e-15);
  EXPECT_NEAR(wheels.right, 1.1, 1e-15);
}

}  // namespace
}  // namespace robodds::odometry_sensor
