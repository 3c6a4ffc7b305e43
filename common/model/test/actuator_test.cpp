#include "common/model/actuator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/model/diff_drive_kinematics.hpp"

namespace robodds::model {
namespace {

constexpr double kTrack = 0.3;  // m
constexpr double kMaxWheel = 1.5;  // m/s

TEST(Actuator, WheelSpeedsAreTheInverseOfTwistFromWheelSpeeds) {
  const WheelSpeeds w = wheel_speeds_from_twist(Twist{1.0, 2.0}, kTrack);
  EXPECT_DOUBLE_EQ(w.left, 0.7);
  EXPECT_DOUBLE_EQ(w.right, 1.3) << "a faster right wheel turns left (omega > 0)";
  const Twist back = twist_from_wheel_speeds(w.left, w.right, kTrack);
  EXPECT_NEAR(back.v, 1.0, 1e-15);
  EXPECT_NEAR(back.omega, 2.0, 1e-14);
}

TEST(Actuator, ClampingEachWheelBendsThePath) {
  // v = 2, omega = 4: wheels 1.4 and 2.6 -> 1.4 and 1.5: v = 1.45, omega = 1/3.
  const Twist t = clamp_wheel_speeds(Twist{2.0, 4.0}, kTrack, kMaxWheel);
  const WheelSpeeds w = wheel_speeds_from_twist(t, kTrack);
  EXPECT_NEAR(w.left, 1.4, 1e-12);
  EXPECT_NEAR(w.right, 1.5, 1e-12);
  EXPECT_GT(std::abs(t.omega / t.v - 4.0 / 2.0), 1.0) << "the curvature changed";
  const Twist within{1.0, 2.0};
  const Twist same = clamp_wheel_speeds(within, kTrack, kMaxWheel);
  EXPECT_EQ(same.v, within.v) << "within the limit: bit-identical";
  EXPECT_EQ(same.omega, within.omega);
  const Twist off = clamp_wheel_speeds(Twist{18.0, 60.0}, kTrack, 0.0);
  EXPECT_EQ(off.v, 18.0) << "0 = unlimited";
  EXPECT_EQ(off.omega, 60.0);
}

TEST(Actuator, ScalingKeepsTheCurvatureAndPutsTheFasterWheelAtTheLimit) {
  for (const Twist& raw : {Twist{18.0, 60.0}, Twist{-3.0, 1.0}, Twist{0.0, -40.0}, Twist{5.0, 0.0}}) {
    const Twist t = scale_to_wheel_limit(raw, kTrack, kMaxWheel);
    const WheelSpeeds w = wheel_speeds_from_twist(t, kTrack);
    EXPECT_NEAR(std::max(std::abs(w.left), std::abs(w.right)), kMaxWheel, 1e-12) << raw.v << ", " << raw.omega;
    EXPECT_NEAR(t.v * raw.omega, t.omega * raw.v, 1e-9) << "same curvature: omega / v kept";
    EXPECT_GE(t.v * raw.v, 0.0) << "same direction";
  }
  const Twist within{1.0, 2.0};
  const Twist same = scale_to_wheel_limit(within, kTrack, kMaxWheel);
  EXPECT_EQ(same.v, 1.0);
  EXPECT_EQ(same.omega, 2.0);
  EXPECT_EQ(scale_to_wheel_limit(Twist{18.0, 60.0}, kTrack, 0.0).v, 18.0) << "0 = unlimited";
}

TEST(Actuator, AccelerationLimitsScaleTheChangeAndStayOnTheSegment) {
  const ActuatorLimits limits{0.0, 1.0, 5.0};
  const double dt = 0.01;
  // From rest towards (1.5, 0): the speed grows by 1 m/s^2 * 0.01 s.
  Twist t = limit_acceleration(Twist{1.5, 0.0}, Twist{}, dt, limits);
  EXPECT_DOUBLE_EQ(t.v, 0.01);
  EXPECT_DOUBLE_EQ(t.omega, 0.0);
  // Towards (1, 10): omega binds (0.05 rad/s per step) and v moves by the same fraction.
  t = limit_acceleration(Twist{1.0, 10.0}, Twist{}, dt, limits);
  EXPECT_NEAR(t.omega, 0.05, 1e-15);
  EXPECT_NEAR(t.v, 0.005, 1e-15) << "on the segment previous -> target";
  // Within the limits: the target exactly.
  const Twist near{0.505, 0.02};
  const Twist exact = limit_acceleration(near, Twist{0.5, 0.0}, dt, limits);
  EXPECT_EQ(exact.v, near.v);
  EXPECT_EQ(exact.omega, near.omega);
  // Unlimited: any jump.
  EXPECT_EQ(limit_acceleration(Twist{300.0, 60.0}, Twist{}, dt, ActuatorLimits{}).v, 300.0);
  // No time: nothing changes.
  EXPECT_EQ(limit_acceleration(Twist{1.0, 1.0}, Twist{0.2, 0.1}, 0.0, limits).v, 0.2);
}

TEST(Actuator, RampingBetweenFeasibleTwistsNeverBreaksTheWheelLimit) {
  // Repeatedly retargeting between corners of the wheel-limit diamond: every step stays inside it
  // and within the acceleration limits.
  const ActuatorLimits limits{kMaxWheel, 1.0, 5.0};
  const double dt = 0.01;
  const Twist corners[] = {{1.5, 0.0}, {0.0, 10.0}, {-1.5, 0.0}, {0.0, -10.0}, {0.75, 5.0}};
  Twist applied{};
  for (int k = 0; k < 4000; ++k) {
    const Twist target = clamp_wheel_speeds(corners[(k / 300) % 5], kTrack, kMaxWheel);
    const Twist next = limit_acceleration(target, applied, dt, limits);
    const WheelSpeeds w = wheel_speeds_from_twist(next, kTrack);
    ASSERT_LE(std::max(std::abs(w.left), std::abs(w.right)), kMaxWheel + 1e-12) << "step " << k;
    ASSERT_LE(std::abs(next.v - applied.v), limits.max_accel_mps2 * dt + 1e-12) << "step " << k;
    ASSERT_LE(std::abs(next.omega - applied.omega), limits.max_angular_accel_radps2 * dt + 1e-12) << "step " << k;
    applied = next;
  }
}

}  // namespace
}  // namespace robodds::model
