#include "sim/plant/disturbance.hpp"

#include <gtest/gtest.h>

#include "common/angle.hpp"

namespace robodds::plant {
namespace {

TEST(PoseDisturbance, OffByDefault) {
  const PoseDisturbance off;
  EXPECT_FALSE(off.enabled());
  EXPECT_FALSE(off.due(0.0, false));
  EXPECT_FALSE(off.due(1e6, false));
}

TEST(PoseDisturbance, DueOnceFromItsTimeOn) {
  PoseDisturbance d;
  d.at_s = 30.0;
  EXPECT_FALSE(d.due(29.99, false));
  EXPECT_TRUE(d.due(3000 * 0.01, false)) << "3000 steps of 0.01 s are 30 s, whatever the rounding";
  EXPECT_TRUE(d.due(30.5, false));
  EXPECT_FALSE(d.due(30.5, true)) << "once only";
  d.at_s = 0.0;
  EXPECT_TRUE(d.due(0.0, false)) << "at_s = 0 is on: the first step";
}

TEST(PoseDisturbance, MovesThePoseInTheWorldFrameAndWrapsTheHeading) {
  PoseDisturbance d;
  d.at_s = 1.0;
  d.dx_m = 10.0;
  d.dy_m = -2.0;
  d.dtheta_rad = 0.5 * kPi;
  const model::Pose2 moved = apply_disturbance(model::Pose2{1.0, 2.0, 0.75 * kPi}, d);
  EXPECT_DOUBLE_EQ(moved.x, 11.0) << "world frame, not body frame";
  EXPECT_DOUBLE_EQ(moved.y, 0.0);
  EXPECT_NEAR(moved.theta, -0.75 * kPi, 1e-12) << "wrapped to (-pi, pi]";
}

}  // namespace
}  // namespace robodds::plant
