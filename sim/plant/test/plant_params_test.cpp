#include "sim/plant/plant_params.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

namespace robodds::plant {
namespace {

std::string message_of(const PlantParams& p) {
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(PlantParams, DefaultsAreValid) { EXPECT_EQ(message_of(PlantParams{}), ""); }

TEST(PlantParams, EachBadValueNamesItsKey) {
  PlantParams p;
  p.wheel_base_m = 0.0;
  EXPECT_EQ(message_of(p).rfind("wheel_base_m:", 0), 0u);
  p = PlantParams{};
  p.wheel_base_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message_of(p).rfind("wheel_base_m:", 0), 0u);
  p = PlantParams{};
  p.limits.max_speed_mps = -1.0;
  EXPECT_EQ(message_of(p).rfind("max_speed_mps:", 0), 0u);
  p = PlantParams{};
  p.limits.max_turn_rate_radps = -1.0;
  EXPECT_EQ(message_of(p).rfind("max_turn_rate_radps:", 0), 0u);
  p = PlantParams{};
  p.command_timeout_s = 0.0;
  EXPECT_EQ(message_of(p).rfind("command_timeout_s:", 0), 0u);
}

}  // namespace
}  // namespace robodds::plant
