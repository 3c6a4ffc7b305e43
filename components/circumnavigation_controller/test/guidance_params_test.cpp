#include "components/circumnavigation_controller/guidance_params.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "tests/support/validation_error.hpp"

namespace robodds::circumnavigation_controller {
namespace {

using test_support::validation_error;

bool starts_with(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

TEST(GuidanceParams, DefaultsAreThoseOfTheIssuePrototypeAndPass) {
  const GuidanceParams p;
  EXPECT_EQ(validation_error(p), "");
  EXPECT_EQ(p.cruise_speed_mps, 10.0);
  EXPECT_EQ(p.approach_gain, 0.8);
  EXPECT_EQ(p.approach_width_m, 100.0);
  EXPECT_EQ(p.heading_gain, 0.02);
  EXPECT_EQ(p.max_turn_rate_radps, 0.15);
  EXPECT_EQ(p.spacing_gain, 0.5);
  EXPECT_EQ(p.spacing_saturation, 0.3);
  EXPECT_EQ(p.max_accel_mps2, 0.5);
  EXPECT_DOUBLE_EQ(max_commanded_speed(p), 13.0);
}

TEST(GuidanceParams, EachBadValueNamesItsKey) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    double GuidanceParams::*field;
    double value;
    const char* message_start;
  };
  const Case cases[] = {
      {&GuidanceParams::cruise_speed_mps, 0.0, "cruise_speed_mps: must be > 0"},
      {&GuidanceParams::cruise_speed_mps, -10.0, "cruise_speed_mps: must be > 0"},
      {&GuidanceParams::approach_gain, 0.0, "approach_gain: must be > 0"},
      {&GuidanceParams::approach_gain, 1.01, "approach_gain: must be in (0, 1]"},
      {&GuidanceParams::approach_width_m, 0.0, "approach_width_m: must be > 0"},
      {&GuidanceParams::heading_gain, nan, "heading_gain: must be > 0"},
      {&GuidanceParams::max_turn_rate_radps, 0.0, "max_turn_rate_radps: must be > 0"},
      {&GuidanceParams::spacing_gain, -0.1, "spacing_gain: must be >= 0"},
      {&GuidanceParams::spacing_saturation, 1.0, "spacing_saturation: must be in [0, 1)"},
      {&GuidanceParams::spacing_saturation, -0.1, "spacing_saturation: must be >= 0"},
      {&GuidanceParams::max_accel_mps2, 0.0, "max_accel_mps2: must be > 0"},
  };
  for (const Case& c : cases) {
    GuidanceParams p;
    p.*(c.field) = c.value;
    const std::string error = validation_error(p);
    EXPECT_TRUE(starts_with(error, c.message_start)) << error;
  }
}

TEST(GuidanceParams, EdgesOfTheRangesPass) {
  GuidanceParams p;
  p.approach_gain = 1.0;
  p.spacing_gain = 0.0;
  p.spacing_saturation = 0.0;
  EXPECT_EQ(validation_error(p), "");
}

TEST(GuidanceParams, TableListsEveryKeyOnce) {
  const auto doc = guidance_param_table().doc();
  std::vector<std::string> keys;
  for (const auto& info : doc.params) {
    keys.push_back(info.key);
  }
  EXPECT_EQ(keys, (std::vector<std::string>{"cruise_speed_mps", "approach_gain", "approach_width_m", "heading_gain",
                                            "max_turn_rate_radps", "spacing_gain", "spacing_saturation",
                                            "max_accel_mps2", "start_cruising"}));
}

}  // namespace
}  // namespace robodds::circumnavigation_controller
