#include "common/angle.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/random.hpp"

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
  EXPECT_TRUE(std::isinf(wrap_angle(std::numeric_limits<double>::infinity())));
}

TEST(WrapAngle, FastPathIsBitIdenticalToTheRemainder) {
  RandomEngine engine(1);
  for (int i = 0; i < 200000; ++i) {
    // Mostly the fast path's range (-3 pi, 3 pi), plus some far excursions.
    const double scale = (i % 10 == 0) ? 100.0 : 3.0;
    const double angle = scale * kPi * (2.0 * uniform01(engine) - 1.0);
    ASSERT_EQ(wrap_angle(angle), wrap_angle_by_remainder(angle)) << "angle " << angle;
  }
}

TEST(WrapAngle, EdgesOfTheFastPathMatchTheRemainder) {
  for (const double angle : {kPi, -kPi, 2.0 * kPi, -2.0 * kPi, 3.0 * kPi, -3.0 * kPi,
                             std::nextafter(kPi, 10.0), std::nextafter(-kPi, -10.0),
                             std::nextafter(3.0 * kPi, 0.0), std::nextafter(-3.0 * kPi, 0.0), 0.0, -0.0}) {
    EXPECT_EQ(wrap_angle(angle), wrap_angle_by_remainder(angle)) << "angle " << angle;
    EXPECT_GT(wrap_angle(angle), -kPi);
    EXPECT_LE(wrap_angle(angle), kPi);
  }
}

}  // namespace
}  // namespace robodds
