#include "common/model/twist.hpp"

#include <gtest/gtest.h>

namespace robodds::model {
namespace {

TEST(Twist, SaturateClampsEachAxisAndZeroMeansUnlimited) {
  const Twist t = saturate({-5.0, 3.0}, {1.0, 0.5});
  EXPECT_DOUBLE_EQ(t.v, -1.0);
  EXPECT_DOUBLE_EQ(t.omega, 0.5);
  const Twist free = saturate({-5.0, 3.0}, {});
  EXPECT_DOUBLE_EQ(free.v, -5.0);
  EXPECT_DOUBLE_EQ(free.omega, 3.0);
}

}  // namespace
}  // namespace robodds::model
