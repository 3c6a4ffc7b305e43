#include "components/waypoint_controller/polar.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angle.hpp"

namespace robodds::waypoint_controller {
namespace {

constexpr double kTol = 1e-12;

double degrees(double deg) { return deg * kPi / 180.0; }

PolarError from_origin(double theta_rad, double waypoint_x, double waypoint_y) {
  return polar_error(Eigen::Vector2d(0.0, 0.0), theta_rad, Eigen::Vector2d(waypoint_x, waypoint_y));
}

TEST(WaypointPolar, BearingPointsFromRobotToWaypointInEveryQuadrant) {
  struct Case {
    double x, y, alpha;
  };
  const Case cases[] = {
      {1.0, 0.0, 0.0},         {1.0, 1.0, kPi / 4},       {0.0, 1.0, kPi / 2},       {-1.0, 1.0, 3 * kPi / 4},
      {-1.0, 0.0, kPi},        {-1.0, -1.0, -3 * kPi / 4}, {0.0, -1.0, -kPi / 2},     {1.0, -1.0, -kPi / 4},
  };
  for (const Case& c : cases) {
    const PolarError error = from_origin(0.0, c.x, c.y);
    EXPECT_NEAR(error.alpha_rad, c.alpha, kTol) << c.x << ", " << c.y;
    EXPECT_NEAR(error.distance_m, std::hypot(c.x, c.y), kTol);
  }
}

TEST(WaypointPolar, WaypointDirectlyBehindIsPlusPi) {
  // wrap_angle maps to (-pi, pi]: behind is +pi, never -pi.
  EXPECT_EQ(from_origin(0.0, -3.0, 0.0).alpha_rad, kPi);
}

TEST(WaypointPolar, BearingIsRelativeToHeading) {
  // Heading north, way-point to the east: it is on the right (alpha = -pi/2).
  EXPECT_NEAR(from_origin(kPi / 2, 5.0, 0.0).alpha_rad, -kPi / 2, kTol);
  // Heading north-east towards a way-point to the north-east: straight ahead.
  EXPECT_NEAR(polar_error(Eigen::Vector2d(50.0, 10.0), kPi / 4, Eigen::Vector2d(60.0, 20.0)).alpha_rad, 0.0, kTol);
}

TEST(WaypointPolar, AlphaWrapsAcrossPi) {
  // Heading 170 deg, way-point at bearing -170 deg: 20 deg to the left, not -340.
  const PolarError error = from_origin(degrees(170.0), std::cos(degrees(-170.0)), std::sin(degrees(-170.0)));
  EXPECT_NEAR(error.alpha_rad, degrees(20.0), 1e-9);
  // And the mirror case: heading -170 deg, way-point at 170 deg: 20 deg to the right.
  const PolarError mirror = from_origin(degrees(-170.0), std::cos(degrees(170.0)), std::sin(degrees(170.0)));
  EXPECT_NEAR(mirror.alpha_rad, degrees(-20.0), 1e-9);
}

TEST(WaypointPolar, SigmaIsHalfPiMinusHeadingWrapped) {
  EXPECT_NEAR(from_origin(0.0, 1.0, 0.0).sigma_rad, kPi / 2, kTol);
  EXPECT_NEAR(from_origin(kPi / 2, 1.0, 0.0).sigma_rad, 0.0, kTol);
  EXPECT_NEAR(from_origin(kPi, 1.0, 0.0).sigma_rad, -kPi / 2, kTol);
  EXPECT_NEAR(from_origin(-kPi / 2, 1.0, 0.0).sigma_rad, kPi, kTol);
  EXPECT_NEAR(from_origin(-3 * kPi / 4, 1.0, 0.0).sigma_rad, -3 * kPi / 4, kTol);
}

TEST(WaypointPolar, SigmaDoesNotDependOnTheWaypoint) {
  EXPECT_EQ(from_origin(0.3, 1.0, 0.0).sigma_rad, from_origin(0.3, -7.0, 2.0).sigma_rad);
}

TEST(WaypointPolar, UnwrappedHeadingGivesTheSameResult) {
  const PolarError wrapped = from_origin(0.1, 2.0, 3.0);
  const PolarError unwrapped = from_origin(0.1 + 4 * kPi, 2.0, 3.0);
  EXPECT_NEAR(unwrapped.alpha_rad, wrapped.alpha_rad, 1e-12);
  EXPECT_NEAR(unwrapped.sigma_rad, wrapped.sigma_rad, 1e-12);
}

TEST(WaypointPolar, OnTheWaypointAlphaIsZeroAndEverythingFinite) {
  const PolarError error = polar_error(Eigen::Vector2d(3.0, -4.0), 1.0, Eigen::Vector2d(3.0, -4.0));
  EXPECT_EQ(error.distance_m, 0.0);
  EXPECT_EQ(error.alpha_rad, 0.0);  // not atan2(0, 0) - theta = -1
  EXPECT_NEAR(error.sigma_rad, kPi / 2 - 1.0, kTol);
}

TEST(WaypointPolar, TinyDistanceStillHasABearing) {
  const PolarError error = from_origin(0.0, 0.0, 1e-300);
  EXPECT_GT(error.distance_m, 0.0);
  EXPECT_NEAR(error.alpha_rad, kPi / 2, kTol);
}

}  // namespace
}  // namespace robodds::waypoint_controller
