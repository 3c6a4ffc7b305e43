// RouteFollower's sequencing: vertex switching, turn in place then drive, loop wrap, the stop at
// the end of an open route, realignment, bad input.
#include "components/route_follower/route_follower.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/angle.hpp"

namespace robodds::route_follower {
namespace {

constexpr double kDt = 0.02;

RouteParams square(bool loop) {
  RouteParams params;
  params.route = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  params.loop = loop;
  return params;
}

TEST(RouteFollower, StartingOnVertexZeroTurnsInPlaceTowardsVertexOne) {
  RouteFollower follower(square(true));
  const FollowerOutput out = follower.step(model::Pose2{0.01, 0.0, kPi / 2}, kDt);  // facing north, vertex 1 east
  EXPECT_TRUE(out.status.reached_this_step);
  EXPECT_EQ(out.status.target_index, 1u);
  EXPECT_EQ(out.status.reached_count, 1u);
  EXPECT_EQ(out.status.phase, Phase::kTurning);
  EXPECT_EQ(out.twist.v, 0.0) << "turn in place";
  EXPECT_DOUBLE_EQ(out.twist.omega, -0.5) << "right (the shorter way) at the turn rate";
}

TEST(RouteFollower, AlignedItDrivesAtSpeedWithASmallCorrection) {
  RouteFollower follower(square(true));
  follower.step(model::Pose2{0.0, 0.0, 0.0}, kDt);  // reaches vertex 0, already facing vertex 1
  const FollowerOutput out = follower.step(model::Pose2{0.5, 0.01, 0.0}, kDt);
  EXPECT_EQ(out.status.phase, Phase::kDriving);
  EXPECT_DOUBLE_EQ(out.twist.v, 0.2);
  EXPECT_NEAR(out.status.cross_track_m, 0.01, 1e-12);
  EXPECT_LT(out.twist.omega, 0.0) << "1 cm left of the segment: steer right";
  EXPECT_GT(out.twist.omega, -0.1);
}

TEST(RouteFollower, TheTurnEndsWithinTheHeadingTolerance) {
  RouteFollower follower(square(true));
  follower.step(model::Pose2{0.0, 0.0, 0.5}, kDt);
  EXPECT_EQ(follower.phase(), Phase::kTurning);
  const FollowerOutput out = follower.step(model::Pose2{0.0, 0.0, 0.019}, kDt);  // tolerance 0.02 rad
  EXPECT_EQ(out.status.phase, Phase::kDriving);
  EXPECT_DOUBLE_EQ(out.twist.v, 0.2);
}

TEST(RouteFollower, SwitchesWithinThePositionToleranceAndWrapsTheLoop) {
  RouteFollower follower(square(true));
  follower.step(model::Pose2{0.0, 0.0, 0.0}, kDt);
  FollowerOutput out = follower.step(model::Pose2{1.94, 0.0, 0.0}, kDt);  // 0.06 m from vertex 1
  EXPECT_FALSE(out.status.reached_this_step);
  out = follower.step(model::Pose2{1.96, 0.0, 0.0}, kDt);
  EXPECT_TRUE(out.status.reached_this_step);
  EXPECT_EQ(out.status.target_index, 2u);
  EXPECT_EQ(out.twist.v, 0.0);
  EXPECT_DOUBLE_EQ(out.twist.omega, 0.5) << "left towards (2, 2)";
  follower.step(model::Pose2{2.0, 1.97, kPi / 2}, kDt);  // vertex 2
  out = follower.step(model::Pose2{0.03, 2.0, kPi}, kDt);  // vertex 3
  EXPECT_EQ(out.status.target_index, 0u) << "loop: after the last vertex the first";
  EXPECT_EQ(out.status.reached_count, 4u);
  EXPECT_FALSE(follower.done());
}

TEST(RouteFollower, AnOpenRouteStopsAtItsLastPointForGood) {
  RouteFollower follower(square(false));
  follower.step(model::Pose2{0.0, 0.0, 0.0}, kDt);
  follower.step(model::Pose2{2.0, 0.0, kPi / 2}, kDt);
  follower.step(model::Pose2{2.0, 2.0, kPi}, kDt);
  FollowerOutput out = follower.step(model::Pose2{0.0, 2.0, kPi}, kDt);
  EXPECT_TRUE(out.status.reached_this_step);
  EXPECT_EQ(out.status.phase, Phase::kDone);
  EXPECT_TRUE(follower.done());
  EXPECT_EQ(out.twist.v, 0.0);
  EXPECT_EQ(out.twist.omega, 0.0);
  out = follower.step(model::Pose2{1.0, 1.0, 0.3}, kDt);  // pushed away: stays stopped
  EXPECT_EQ(out.twist.v, 0.0);
  EXPECT_EQ(out.twist.omega, 0.0);
  EXPECT_EQ(follower.reached_count(), 4u);
}

TEST(RouteFollower, AHeadingErrorBeyondTheThresholdStopsAndTurnsAgain) {
  RouteFollower follower(square(true));
  follower.step(model::Pose2{0.0, 0.0, 0.0}, kDt);
  EXPECT_EQ(follower.step(model::Pose2{1.0, 0.0, 0.4}, kDt).status.phase, Phase::kDriving) << "0.4 < 0.5 rad";
  const FollowerOutput out = follower.step(model::Pose2{1.0, 0.0, 0.6}, kDt);
  EXPECT_EQ(out.status.phase, Phase::kTurning);
  EXPECT_EQ(out.twist.v, 0.0);
  EXPECT_DOUBLE_EQ(out.twist.omega, -0.5);
}

TEST(RouteFollower, PastTheVertexBesideTheCircleItTurnsBackToIt) {
  RouteFollower follower(square(true));
  follower.step(model::Pose2{0.0, 0.0, 0.0}, kDt);
  const FollowerOutput out = follower.step(model::Pose2{2.3, 0.1, 0.0}, kDt);  // missed (2, 0) by 0.1 m
  EXPECT_FALSE(out.status.reached_this_step);
  EXPECT_EQ(out.status.target_index, 1u);
  EXPECT_EQ(out.status.phase, Phase::kTurning);
  EXPECT_EQ(out.twist.v, 0.0);
}

TEST(RouteFollower, AStartOffTheRouteDrivesToVertexZeroFirst) {
  RouteFollower follower(square(true));
  const FollowerOutput out = follower.step(model::Pose2{-1.0, 0.0, 0.0}, kDt);
  EXPECT_EQ(out.status.target_index, 0u);
  EXPECT_EQ(out.status.reached_count, 0u);
  EXPECT_EQ(out.status.phase, Phase::kDriving);
  EXPECT_DOUBLE_EQ(out.twist.v, 0.2);
  EXPECT_DOUBLE_EQ(out.status.distance_to_target_m, 1.0);
}

TEST(RouteFollower, NonFinitePoseOrBadPeriodThrowsAndChangesNothing) {
  RouteFollower follower(square(true));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(follower.step(model::Pose2{nan, 0.0, 0.0}, kDt), std::invalid_argument);
  EXPECT_THROW(follower.step(model::Pose2{0.0, 0.0, 0.0}, 0.0), std::invalid_argument);
  EXPECT_EQ(follower.reached_count(), 0u);
  EXPECT_EQ(follower.step(model::Pose2{0.0, 0.0, 0.0}, kDt).status.reached_count, 1u);
}

TEST(RouteFollower, BadParamsThrowNamingTheKey) {
  RouteParams params;
  params.route = {{0, 0}};
  try {
    RouteFollower follower(params);
    FAIL() << "one point accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("route: ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace robodds::route_follower
