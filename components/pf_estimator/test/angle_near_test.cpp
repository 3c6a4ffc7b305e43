#include "components/pf_estimator/angle_near.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/random.hpp"

namespace robodds::pf {
namespace {

TEST(WrapAngleNear, IsBitIdenticalToWrapAngle) {
  RandomEngine engine(1);
  for (int i = 0; i < 200000; ++i) {
    // Mostly the filter's range (-3 pi, 3 pi), plus some far excursions.
    const double scale = (i % 10 == 0) ? 100.0 : 3.0;
    const double angle = scale * kPi * (2.0 * uniform01(engine) - 1.0);
    ASSERT_EQ(wrap_angle_near(angle), wrap_angle(angle)) << "angle " << angle;
  }
}

TEST(WrapAngleNear, HandlesTheEdgesOfTheRange) {
  for (const double angle : {kPi, -kPi, 2.0 * kPi, -2.0 * kPi, 3.0 * kPi, -3.0 * kPi,
                             std::nextafter(kPi, 10.0), std::nextafter(-kPi, -10.0), 0.0, -0.0}) {
    EXPECT_EQ(wrap_angle_near(angle), wrap_angle(angle)) << "angle " << angle;
    EXPECT_GT(wrap_angle_near(angle), -kPi);
    EXPECT_LE(wrap_angle_near(angle), kPi);
  }
  EXPECT_TRUE(std::isnan(wrap_angle_near(std::numeric_limits<double>::quiet_NaN())));
}

}  // namespace
}  // namespace robodds::pf
