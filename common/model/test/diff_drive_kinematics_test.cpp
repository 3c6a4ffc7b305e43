#include "common/model/diff_drive_kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angle.hpp"

namespace robodds::model {
namespace {

TEST(DiffDriveKinematics, WheelSpeedsToTwist) {
  const Twist t = twist_from_wheel_speeds(1.0, 3.0, 0.5);
  EXPECT_DOUBLE_EQ(t.v, 2.0);
  EXPECT_DOUBLE_EQ(t.omega, 4.0);  // faster right wheel turns counter-clockwise
}

TEST(DiffDriveKinematics, StraightLineWhenOmegaIsZero) {
  const Pose2 end = integrate_exact({1.0, 2.0, kPi / 3.0}, {2.0, 0.0}, 1.5);
  EXPECT_NEAR(end.x, 1.0 + 3.0 * std::cos(kPi / 3.0), 1e-12);
  EXPECT_NEAR(end.y, 2.0 + 3.0 * std::sin(kPi / 3.0), 1e-12);
  EXPECT_NEAR(end.theta, kPi / 3.0, 1e-15);
}

TEST(DiffDriveKinematics, MatchesClosedFormArc) {
  const Pose2 start{0.5, -1.0, 0.3};
  const Twist twist{1.2, 0.7};
  const double dt = 0.9;
  const double r = twist.v / twist.omega;
  const Pose2 end = integrate_exact(start, twist, dt);
  EXPECT_NEAR(end.x, start.x + r * (std::sin(start.theta + twist.omega * dt) - std::sin(start.theta)), 1e-12);
  EXPECT_NEAR(end.y, start.y + r * (std::cos(start.theta) - std::cos(start.theta + twist.omega * dt)), 1e-12);
  EXPECT_NEAR(end.theta, start.theta + twist.omega * dt, 1e-12);
}

TEST(DiffDriveKinematics, SincSeriesMatchesSinOverXAndIsContinuousAtItsSwitch) {
  EXPECT_EQ(sinc(0.0), 1.0);
  // Against sin(x)/x in long double: the series branch (|x| < 0.1) is exact to double rounding,
  // including just below the switch; the sin branch just above it agrees as well.
  const auto reference = [](double x) { return static_cast<double>(std::sin(static_cast<long double>(x)) / x); };
  for (double x = -0.2; x <= 0.2; x += 1e-4) {
    if (x == 0.0) continue;
    EXPECT_NEAR(sinc(x), reference(x), 2.5e-16) << "x " << x;
  }
  for (const double edge : {0.1, -0.1}) {
    EXPECT_NEAR(sinc(std::nextafter(edge, 0.0)), reference(std::nextafter(edge, 0.0)), 2.5e-16);
    EXPECT_NEAR(sinc(std::nextafter(edge, 0.0)), sinc(edge), 1e-15);  // no step at the switch
  }
}

TEST(DiffDriveKinematics, TinyOmegaIsContinuousWithTheStraightLine) {
  const Pose2 straight = integrate_exact({0, 0, 0.2}, {1.0, 0.0}, 0.01);
  const Pose2 almost = integrate_exact({0, 0, 0.2}, {1.0, 1e-9}, 0.01);
  EXPECT_NEAR(straight.x, almost.x, 1e-12);
  EXPECT_NEAR(straight.y, almost.y, 1e-12);
}

TEST(DiffDriveKinematics, FullCircleReturnsToStart) {
  Pose2 pose{3.0, 4.0, 0.0};
  const int n = 1000;
  for (int i = 0; i < n; ++i) {
    pose = integrate_exact(pose, {1.0, 2.0 * kPi}, 1.0 / n);
  }
  EXPECT_NEAR(pose.x, 3.0, 1e-9);
  EXPECT_NEAR(pose.y, 4.0, 1e-9);
  EXPECT_NEAR(wrap_angle(pose.theta), 0.0, 1e-9);
}

TEST(DiffDriveKinematics, TurnInPlace) {
  const Pose2 end = integrate_exact({1.0, 1.0, 0.0}, {0.0, 1.0}, 0.5);
  EXPECT_DOUBLE_EQ(end.x, 1.0);
  EXPECT_DOUBLE_EQ(end.y, 1.0);
  EXPECT_NEAR(end.theta, 0.5, 1e-15);
}

}  // namespace
}  // namespace robodds::model
