#include "components/range_rate_observer/observer_params.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "tests/support/validation_error.hpp"

namespace robodds::range_rate_observer {
namespace {

using test_support::validation_error;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

TEST(SuperTwistingParams, DefaultsAreValid) { EXPECT_EQ(validation_error(SuperTwistingParams{}), ""); }

TEST(SuperTwistingParams, GainARangeFromThePaper) {
  for (const double a : {0.0, -1.0, 2.5, 3.0, kNan}) {
    SuperTwistingParams p;
    p.a = a;
    EXPECT_EQ(validation_error(p).rfind("a: must be in (0, 2.5)", 0), 0u) << a;
  }
  SuperTwistingParams p;
  p.a = 2.49;
  EXPECT_EQ(validation_error(p), "");
}

TEST(SuperTwistingParams, EachBadGainNamesItsKey) {
  SuperTwistingParams p;
  p.b = 0.0;
  EXPECT_EQ(validation_error(p), "b: must be > 0 and finite (got 0)");
  p = SuperTwistingParams{};
  p.c = -1.0;  // the sign printed in eq. (2), which diverges
  EXPECT_EQ(validation_error(p), "c: must be > 0 and finite (got -1)");
  p = SuperTwistingParams{};
  p.d = -0.5;
  EXPECT_EQ(validation_error(p), "d: must be >= 0 and finite (0 = plain super-twisting) (got -0.5)");
  p = SuperTwistingParams{};
  p.d = 0.0;
  EXPECT_EQ(validation_error(p), "");
  p.restart_sigmas = kNan;
  EXPECT_EQ(validation_error(p).rfind("restart_sigmas: ", 0), 0u);
  p = SuperTwistingParams{};
  p.restart_sigmas = -1.0;
  EXPECT_EQ(validation_error(p), "restart_sigmas: must be >= 0 and finite (0 = never restart) (got -1)");
  p = SuperTwistingParams{};
  p.noise_floor_m = 0.0;  // noise-free, the missed steps are millimetres: no floor, no threshold
  EXPECT_EQ(validation_error(p), "noise_floor_m: must be > 0 and finite (got 0)");
  p = SuperTwistingParams{};
  p.restart_window_s = 0.0;
  EXPECT_EQ(validation_error(p), "restart_window_s: must be > 0 and finite (got 0)");
}

TEST(LinearObserverParams, DefaultsAreValidAndBadGainsNamed) {
  EXPECT_EQ(validation_error(LinearObserverParams{}), "");
  LinearObserverParams p;
  p.k1 = 0.0;
  EXPECT_EQ(validation_error(p), "k1: must be > 0 and finite (got 0)");
  p = LinearObserverParams{};
  p.k2 = kNan;
  EXPECT_EQ(validation_error(p), "k2: must be > 0 and finite (got nan)");
  p = LinearObserverParams{};
  p.restart_window_s = -0.5;
  EXPECT_EQ(validation_error(p), "restart_window_s: must be > 0 and finite (got -0.5)");
}

TEST(ObserverParamTables, DocumentEveryFieldWithItsDefault) {
  const params::ParamDoc doc = super_twisting_param_table().doc();
  ASSERT_EQ(doc.params.size(), 7u);
  EXPECT_EQ(doc.params[0].key, "a");
  EXPECT_EQ(doc.params[0].default_yaml, "2.12");
  EXPECT_EQ(doc.params[0].range, "(0, 2.5)");
  EXPECT_EQ(doc.params[3].range, ">= 0 (0 = plain super-twisting)");
  const params::ParamDoc linear = linear_observer_param_table().doc();
  ASSERT_EQ(linear.params.size(), 5u);
  EXPECT_EQ(linear.params[1].key, "k2");
  EXPECT_EQ(linear.params[1].default_yaml, "2.25");
}

}  // namespace
}  // namespace robodds::range_rate_observer
