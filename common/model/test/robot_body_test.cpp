#include "common/model/robot_body.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "tests/support/validation_error.hpp"

namespace robodds::model {
namespace {

using test_support::validation_error;

TEST(RobotBody, DefaultsAreValidAndUnlimited) {
  const RobotBody body;
  EXPECT_EQ(validation_error(body), "");
  EXPECT_EQ(body.wheel_base_m, 0.5);
  EXPECT_EQ(body.limits.max_speed_mps, 0.0);
  EXPECT_EQ(body.actuator.max_wheel_speed_mps, 0.0);
}

TEST(RobotBody, EachBadValueNamesItsKey) {
  RobotBody b;
  b.wheel_base_m = 0.0;
  EXPECT_EQ(validation_error(b).rfind("wheel_base_m:", 0), 0u);
  b = RobotBody{};
  b.wheel_base_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(validation_error(b).rfind("wheel_base_m:", 0), 0u);
  b = RobotBody{};
  b.limits.max_speed_mps = -1.0;
  EXPECT_EQ(validation_error(b), "max_speed_mps: must be >= 0 and finite (0 = unlimited) (got -1)");
  b.limits.max_speed_mps = std::numeric_limits<double>::infinity();  // 0 means unlimited, not inf
  EXPECT_EQ(validation_error(b).rfind("max_speed_mps:", 0), 0u);
  b = RobotBody{};
  b.limits.max_turn_rate_radps = -1.0;
  EXPECT_EQ(validation_error(b).rfind("max_turn_rate_radps:", 0), 0u);
  b = RobotBody{};
  b.actuator.max_wheel_speed_mps = -1.5;
  EXPECT_EQ(validation_error(b), "max_wheel_speed_mps: must be >= 0 and finite (0 = unlimited) (got -1.5)");
  b = RobotBody{};
  b.actuator.max_accel_mps2 = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validation_error(b).rfind("max_accel_mps2:", 0), 0u);
  b = RobotBody{};
  b.actuator.max_angular_accel_radps2 = -5.0;
  EXPECT_EQ(validation_error(b).rfind("max_angular_accel_radps2:", 0), 0u);
}

TEST(RobotBody, TheTableNamesEveryKeyOnce) {
  const auto doc = robot_body_param_table().doc();
  std::string keys;
  for (const auto& info : doc.params) keys += info.key + " ";
  EXPECT_EQ(keys, "wheel_base_m max_speed_mps max_turn_rate_radps max_wheel_speed_mps max_accel_mps2 max_angular_accel_radps2 ");
}

}  // namespace
}  // namespace robodds::model
