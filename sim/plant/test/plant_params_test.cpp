#include "sim/plant/plant_params.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

#include "tests/support/validation_error.hpp"

namespace robodds::plant {
namespace {

using test_support::validation_error;

TEST(PlantParams, DefaultsAreValid) { EXPECT_EQ(validation_error(PlantParams{}), ""); }

TEST(PlantParams, EachBadValueNamesItsKey) {
  PlantParams p;
  p.wheel_base_m = 0.0;
  EXPECT_EQ(validation_error(p).rfind("wheel_base_m:", 0), 0u);
  p = PlantParams{};
  p.wheel_base_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(validation_error(p).rfind("wheel_base_m:", 0), 0u);
  p = PlantParams{};
  p.limits.max_speed_mps = -1.0;
  EXPECT_EQ(validation_error(p), "max_speed_mps: must be >= 0 and finite (0 = unlimited) (got -1)");
  p.limits.max_speed_mps = std::numeric_limits<double>::infinity();  // 0 means unlimited, not inf
  EXPECT_EQ(validation_error(p).rfind("max_speed_mps:", 0), 0u);
  p = PlantParams{};
  p.limits.max_turn_rate_radps = -1.0;
  EXPECT_EQ(validation_error(p).rfind("max_turn_rate_radps:", 0), 0u);
  p = PlantParams{};
  p.command_timeout_s = 0.0;
  EXPECT_EQ(validation_error(p).rfind("command_timeout_s:", 0), 0u);
}

}  // namespace
}  // namespace robodds::plant
