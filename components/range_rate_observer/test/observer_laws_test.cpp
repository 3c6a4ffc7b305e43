#include "components/range_rate_observer/observer_laws.hpp"

#include <gtest/gtest.h>

namespace robodds::range_rate_observer {
namespace {

TEST(SuperTwistingDerivative, MatchesEquationOne) {
  SuperTwistingParams p;  // a 2.12, b 2.2, c 1, d 1
  const ObserverDerivative up = super_twisting_derivative(p, 0.5, 4.0);
  EXPECT_DOUBLE_EQ(up.range_mps, 0.5 + 2.12 * 2.0 + 1.0 * 4.0);
  EXPECT_DOUBLE_EQ(up.rate_mps2, 2.2 + 1.0 * 4.0);
  const ObserverDerivative down = super_twisting_derivative(p, 0.5, -4.0);
  EXPECT_DOUBLE_EQ(down.range_mps, 0.5 - 2.12 * 2.0 - 4.0);
  EXPECT_DOUBLE_EQ(down.rate_mps2, -2.2 - 4.0);
}

TEST(SuperTwistingDerivative, NoCorrectionAtZeroError) {
  const ObserverDerivative d = super_twisting_derivative(SuperTwistingParams{}, -1.5, 0.0);
  EXPECT_EQ(d.range_mps, -1.5);
  EXPECT_EQ(d.rate_mps2, 0.0);  // sgn(0) = 0
}

TEST(LinearDerivative, MatchesEquationNine) {
  LinearObserverParams p;
  p.k1 = 3.0;
  p.k2 = 2.0;
  const ObserverDerivative d = linear_derivative(p, 1.0, -0.5);
  EXPECT_DOUBLE_EQ(d.range_mps, 1.0 - 1.5);
  EXPECT_DOUBLE_EQ(d.rate_mps2, -1.0);
}

}  // namespace
}  // namespace robodds::range_rate_observer
