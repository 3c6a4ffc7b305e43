// The two motions of the route follower: turn in place and line following.
#include "components/route_follower/route_law.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angle.hpp"

namespace robodds::route_follower {
namespace {

TEST(RouteLaw, TurnInPlaceTurnsTheShorterWayAtTheTurnRate) {
  EXPECT_DOUBLE_EQ(turn_in_place_rate(1.0, 0.5, 0.02), 0.5);
  EXPECT_DOUBLE_EQ(turn_in_place_rate(-1.0, 0.5, 0.02), -0.5);
  EXPECT_DOUBLE_EQ(turn_in_place_rate(kPi, 0.5, 0.02), 0.5);
}

TEST(RouteLaw, TurnInPlaceLandsOnTheHeadingInsteadOfOvershooting) {
  // 0.004 rad left, 0.01 rad per step at full rate: the last step turns only what is left.
  EXPECT_DOUBLE_EQ(turn_in_place_rate(0.004, 0.5, 0.02), 0.2);
  EXPECT_DOUBLE_EQ(turn_in_place_rate(-0.004, 0.5, 0.02), -0.2);
  EXPECT_DOUBLE_EQ(turn_in_place_rate(0.0, 0.5, 0.02), 0.0);
}

TEST(RouteLaw, SegmentErrorIsSignedLeftPositive) {
  const Eigen::Vector2d a(1.0, 1.0);
  const Eigen::Vector2d b(5.0, 1.0);  // heading +x
  SegmentError e = segment_error(Eigen::Vector2d(2.0, 1.3), a, b);
  EXPECT_DOUBLE_EQ(e.heading_rad, 0.0);
  EXPECT_NEAR(e.cross_track_m, 0.3, 1e-12);
  EXPECT_NEAR(e.along_track_m, 1.0, 1e-12);
  e = segment_error(Eigen::Vector2d(2.0, 0.8), a, b);
  EXPECT_NEAR(e.cross_track_m, -0.2, 1e-12);
  // Heading -y (south): its left is +x (east).
  e = segment_error(Eigen::Vector2d(6.1, 3.0), Eigen::Vector2d(6.0, 5.5), Eigen::Vector2d(6.0, 0.5));
  EXPECT_NEAR(e.heading_rad, -kPi / 2, 1e-12);
  EXPECT_NEAR(e.cross_track_m, 0.1, 1e-12);
  EXPECT_NEAR(e.along_track_m, 2.5, 1e-12);
}

TEST(RouteLaw, DegenerateSegmentPointsAtThePosition) {
  const SegmentError e = segment_error(Eigen::Vector2d(0.0, 2.0), Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.0, 0.0));
  EXPECT_NEAR(e.heading_rad, kPi / 2, 1e-12);
  EXPECT_EQ(e.cross_track_m, 0.0);
}

TEST(RouteLaw, LineFollowingSteersBackTowardsTheLine) {
  SegmentError left;
  left.heading_rad = 0.0;
  left.cross_track_m = 0.5;  // left of a line heading +x: steer right
  EXPECT_NEAR(line_following_heading(left, 0.5), -kPi / 4, 1e-12);
  SegmentError on_line;
  on_line.heading_rad = 1.0;
  EXPECT_DOUBLE_EQ(line_following_heading(on_line, 0.5), 1.0);
}

TEST(RouteLaw, LineFollowingRateIsProportionalThenBounded) {
  const RouteParams params;  // gain 2 /s, bound 0.1 rad/s
  EXPECT_NEAR(line_following_rate(0.02, 0.0, params), 0.04, 1e-12);
  EXPECT_NEAR(line_following_rate(0.0, 0.02, params), -0.04, 1e-12);
  EXPECT_DOUBLE_EQ(line_following_rate(1.0, 0.0, params), 0.1);
  EXPECT_DOUBLE_EQ(line_following_rate(-1.0, 0.0, params), -0.1);
  // Across the +-pi seam: desired -3.1 from heading 3.1 is 0.083 rad to the left (wrapped), not 6.2 to the right.
  EXPECT_GT(line_following_rate(-3.1, 3.1, params), 0.0);
}

}  // namespace
}  // namespace robodds::route_follower
