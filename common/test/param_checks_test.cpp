#include "common/param_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/number_text.hpp"

namespace robodds::param_checks {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string error_of(const std::function<void()>& check) {
  try {
    check();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ShortestText, ReadsBackExactly) {
  EXPECT_EQ(shortest_text(0.1), "0.1");
  EXPECT_EQ(shortest_text(-2.5), "-2.5");
  EXPECT_EQ(shortest_text(kNan), "nan");
  EXPECT_EQ(shortest_text(-kInf), "-inf");
  const double third = 1.0 / 3.0;
  EXPECT_EQ(std::stod(shortest_text(third)), third);
}

TEST(ParamChecks, AcceptValidValues) {
  EXPECT_EQ(error_of([] { require_finite("k", -3.0); }), "");
  EXPECT_EQ(error_of([] { require_positive("k", 1e-300); }), "");
  EXPECT_EQ(error_of([] { require_non_negative("k", 0.0); }), "");
}

TEST(ParamChecks, NameKeyRequirementAndValue) {
  EXPECT_EQ(error_of([] { require_finite("gains.kd", kNan); }), "gains.kd: must be finite (got nan)");
  EXPECT_EQ(error_of([] { require_positive("rate_hz", -1.0); }), "rate_hz: must be > 0 and finite (got -1)");
  EXPECT_EQ(error_of([] { require_positive("rate_hz", 0.0); }), "rate_hz: must be > 0 and finite (got 0)");
  EXPECT_EQ(error_of([] { require_positive("rate_hz", kInf); }), "rate_hz: must be > 0 and finite (got inf)");
  EXPECT_EQ(error_of([] { require_non_negative("std", kNan); }), "std: must be >= 0 and finite (got nan)");
  EXPECT_EQ(error_of([] { require_non_negative("max_speed_mps", -0.5, "0 = no limit"); }),
            "max_speed_mps: must be >= 0 and finite (0 = no limit) (got -0.5)");
  EXPECT_EQ(error_of([] { reject("mode", "must be a or b", "c"); }), "mode: must be a or b (got c)");
  EXPECT_EQ(error_of([] { require_in_open_interval("slip", 0.5, -0.5, 0.5); }), "slip: must be in (-0.5, 0.5) (got 0.5)");
  EXPECT_EQ(error_of([] { require_in_open_interval("slip", kNan, -0.5, 0.5); }), "slip: must be in (-0.5, 0.5) (got nan)");
  EXPECT_EQ(error_of([] { require_in_open_interval("slip", 0.49, -0.5, 0.5); }), "");
  EXPECT_EQ(error_of([] { require_at_least("num_particles", 0, 1); }), "num_particles: must be >= 1 (got 0)");
  EXPECT_EQ(error_of([] { require_at_least("num_particles", 1, 1); }), "");
}

}  // namespace
}  // namespace robodds::param_checks
