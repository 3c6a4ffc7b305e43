#include "common/angle.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace robodds {
namespace {

TEST(WrapAngle, KeepsValuesInsideRange) {
  EXPECT_DOUBLE_EQ(wrap_angle(0.0), 0.0);
  EXPECT_DOUBLE_EQ(wrap_angle(1.0), 1.0);
  EXPECT_DOUBLE_EQ(wrap_angle(-1.0), -1.0);
}

TEST(WrapAngle, MapsMinusPiToPi) {
  EXPECT_DOUBLE_EQ(wrap_angle(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrap_angle(-kPi), kPi);
}

TEST(WrapAngle, WrapsMultipleTurns) {
  EXPECT_NEAR(wrap_angle(2.0 * kPi + 0.5), 0.5, 1e-12);
  EXPECT_NEAR(wrap_angle(-6.0 * kPi - 0.5), -0.5, 1e-12);
  EXPECT_NEAR(wrap_angle(3.0 * kPi / 2.0), -kPi / 2.0, 1e-12);
}

TEST(WrapAngle, PassesNonFiniteThrough) {
  EXPECT_TRUE(std::isnan(wrap_angle(std::numeric_limits<double>::quiet_NaN())));
}

}  // namespace
}  // namespace robodds
