#include "common/model/pose2.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angle.hpp"

namespace robodds::model {
namespace {

TEST(Pose2Algebra, ComposeAndBetweenAreInverse) {
  const Pose2 w_a{1.0, 2.0, 0.7};
  const Pose2 a_b{-0.5, 3.0, -2.9};
  const Pose2 w_b = compose(w_a, a_b);
  const Pose2 back = between(w_a, w_b);
  EXPECT_NEAR(back.x, a_b.x, 1e-12);
  EXPECT_NEAR(back.y, a_b.y, 1e-12);
  EXPECT_NEAR(back.theta, a_b.theta, 1e-12);
  const Pose2 quarter = compose(Pose2{0.0, 0.0, kPi / 2.0}, Pose2{1.0, 0.0, 0.0});
  EXPECT_NEAR(quarter.x, 0.0, 1e-12);
  EXPECT_NEAR(quarter.y, 1.0, 1e-12);
}

TEST(Pose2Algebra, ComposeAndBetweenWrapTheHeadingButBetweenUnwrappedDoesNot) {
  const Pose2 w_a{0.0, 0.0, 3.0};
  const Pose2 w_b{1.0, 0.0, -3.0};
  EXPECT_NEAR(compose(w_a, Pose2{0.0, 0.0, 0.5}).theta, 3.5 - 2.0 * kPi, 1e-15);
  EXPECT_NEAR(between(w_a, w_b).theta, 2.0 * kPi - 6.0, 1e-15);
  const double a[3] = {w_a.x, w_a.y, w_a.theta};
  const double b[3] = {w_b.x, w_b.y, w_b.theta};
  double a_b[3];
  between_unwrapped(a, b, a_b);
  EXPECT_DOUBLE_EQ(a_b[2], -6.0);
  // Frame b is 1 m along world +x; seen from a, heading 3 rad (nearly -x), that is nearly behind.
  EXPECT_NEAR(a_b[0], std::cos(3.0), 1e-15);
  EXPECT_NEAR(a_b[1], -std::sin(3.0), 1e-15);
}

TEST(Pose2, ToTextGivesTheShortestTextOfEachValue) {
  EXPECT_EQ(to_text(Pose2{1.5, -2.0, 0.3}), "x=1.5, y=-2, theta=0.3");
}

}  // namespace
}  // namespace robodds::model
