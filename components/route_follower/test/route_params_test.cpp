// RouteParams::validate(): the defaults, and one clear error naming the key for each bad value.
#include "components/route_follower/route_params.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "tests/support/validation_error.hpp"

namespace robodds::route_follower {
namespace {

using test_support::validation_error;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

TEST(RouteParams, DefaultsAreThePaper3RectangleAndPass) {
  const RouteParams params;
  EXPECT_EQ(validation_error(params), "");
  ASSERT_EQ(params.route.size(), 4u);
  EXPECT_EQ(params.route[0], (params::Point2{-3.5, -3.0}));
  EXPECT_EQ(params.route[2], (params::Point2{3.5, 3.0}));
  EXPECT_TRUE(params.loop);
  EXPECT_EQ(params.speed_mps, 0.2);
  EXPECT_EQ(params.turn_rate_radps, 0.5);
}

TEST(RouteParams, TheTWithARepeatedVertexPasses) {
  RouteParams params;
  params.route = {{6, 0.5}, {6, 5.5}, {3, 5.5}, {9, 5.5}, {6, 5.5}};
  EXPECT_EQ(validation_error(params), "") << "a vertex may repeat when it is not next to itself";
  params.loop = false;
  params.route = {{0, 0}, {1, 0}};
  EXPECT_EQ(validation_error(params), "") << "two points are a route";
}

TEST(RouteParams, FewerThanTwoPointsNameTheRoute) {
  RouteParams params;
  params.route = {{1, 2}};
  EXPECT_EQ(validation_error(params), "route: a route needs at least 2 points (got 1 point(s))");
  params.route = {};
  EXPECT_EQ(validation_error(params), "route: a route needs at least 2 points (got 0 point(s))");
}

TEST(RouteParams, NonFiniteCoordinateIsRejected) {
  RouteParams params;
  params.route = {{0, 0}, {1, kNan}};
  EXPECT_EQ(validation_error(params), "route: every coordinate must be finite (got point 1 (1, nan))");
}

TEST(RouteParams, ConsecutivePointsCloserThanTheToleranceAreRejected) {
  RouteParams params;
  params.route = {{0, 0}, {1, 0}, {1, 0.01}, {0, 1}};
  EXPECT_EQ(validation_error(params),
            "route: consecutive points must be at least position_tolerance_m 0.05 m apart (got point 1 (1, 0) and "
            "point 2 (1, 0.01), 0.01 m apart)");
}

TEST(RouteParams, ALoopThatRepeatsItsFirstPointIsRejectedAndAnOpenPathIsNot) {
  RouteParams params;
  params.route = {{0, 0}, {1, 0}, {1, 1}, {0, 0}};
  EXPECT_EQ(validation_error(params),
            "route: consecutive points must be at least position_tolerance_m 0.05 m apart (loop: true joins the last "
            "point to the first; do not repeat it) (got point 3 (0, 0) and point 0 (0, 0), 0 m apart)");
  params.loop = false;
  EXPECT_EQ(validation_error(params), "") << "an open path ending where it started is fine";
}

TEST(RouteParams, SpeedAndTurnRateMustBePositive) {
  RouteParams params;
  params.speed_mps = 0.0;
  EXPECT_EQ(validation_error(params), "speed_mps: must be > 0 and finite (got 0)");
  params = RouteParams{};
  params.turn_rate_radps = -0.5;
  EXPECT_EQ(validation_error(params), "turn_rate_radps: must be > 0 and finite (got -0.5)");
}

TEST(RouteParams, TolerancesMustBePositive) {
  RouteParams params;
  params.position_tolerance_m = 0.0;
  EXPECT_EQ(validation_error(params), "position_tolerance_m: must be > 0 and finite (got 0)");
  params = RouteParams{};
  params.heading_tolerance_rad = 0.0;
  EXPECT_EQ(validation_error(params).rfind("heading_tolerance_rad: must be in (0, ", 0), 0u) << validation_error(params);
  params = RouteParams{};
  params.heading_tolerance_rad = kNan;
  EXPECT_EQ(validation_error(params).rfind("heading_tolerance_rad: ", 0), 0u);
}

TEST(RouteParams, LineFollowingGainsMustBePositive) {
  RouteParams params;
  params.lookahead_m = 0.0;
  EXPECT_EQ(validation_error(params), "lookahead_m: must be > 0 and finite (got 0)");
  params = RouteParams{};
  params.heading_gain = -1.0;
  EXPECT_EQ(validation_error(params), "heading_gain: must be > 0 and finite (got -1)");
  params = RouteParams{};
  params.max_correction_radps = 0.0;
  EXPECT_EQ(validation_error(params), "max_correction_radps: must be > 0 and finite (got 0)");
}

TEST(RouteParams, CorrectionAboveTheTurnRateIsRejected) {
  RouteParams params;
  params.max_correction_radps = 0.6;
  EXPECT_EQ(validation_error(params), "max_correction_radps: must be <= turn_rate_radps 0.5 (got 0.6)");
  params.max_correction_radps = 0.5;
  EXPECT_EQ(validation_error(params), "");
}

TEST(RouteParams, RealignThresholdMustExceedTheHeadingTolerance) {
  RouteParams params;
  params.realign_threshold_rad = 0.02;
  EXPECT_EQ(validation_error(params),
            "realign_threshold_rad: must be > heading_tolerance_rad 0.02 (else the robot turns again as soon as it "
            "drives) (got 0.02)");
}

}  // namespace
}  // namespace robodds::route_follower
