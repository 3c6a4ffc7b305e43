#include "sim/plant/plant_model_params.hpp"

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
  p.command_timeout_s = 0.0;
  EXPECT_EQ(validation_error(p).rfind("command_timeout_s:", 0), 0u);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  p = PlantParams{};
  p.disturbance.at_s = nan;
  EXPECT_EQ(validation_error(p).rfind("disturbance_at_s:", 0), 0u);
  p = PlantParams{};
  p.disturbance.dx_m = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validation_error(p).rfind("disturbance_dx_m:", 0), 0u);
  p = PlantParams{};
  p.disturbance.dy_m = nan;
  EXPECT_EQ(validation_error(p).rfind("disturbance_dy_m:", 0), 0u);
  p = PlantParams{};
  p.disturbance.dtheta_rad = nan;
  EXPECT_EQ(validation_error(p).rfind("disturbance_dtheta_rad:", 0), 0u);
}

}  // namespace
}  // namespace robodds::plant
