#include "components/circumnavigation_controller/guidance_law.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

#include "common/angle.hpp"

namespace robodds::circumnavigation_controller {
namespace {

constexpr double kR = 200.0;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string bound_error(double v_max, double omega_max, double b, const char* b_key = "sta.b") {
  try {
    check_observer_bound(v_max, omega_max, b, b_key);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

Gaps even_gaps(int n) { return Gaps{2.0 * kPi / n, 2.0 * kPi / n, n}; }

TEST(Saturate, ClampsSymmetrically) {
  EXPECT_EQ(saturate(2.0, 1.0), 1.0);
  EXPECT_EQ(saturate(-2.0, 1.0), -1.0);
  EXPECT_EQ(saturate(0.4, 1.0), 0.4);
}

TEST(DesiredRangeRate, ApproachesWhenTooFarRecedesWhenTooCloseZeroOnTheOrbit) {
  const GuidanceParams p;
  EXPECT_DOUBLE_EQ(desired_range_rate(1500.0, kR, 10.0, p), -8.0);  // saturated: -0.8 V
  EXPECT_DOUBLE_EQ(desired_range_rate(250.0, kR, 10.0, p), -4.0);   // -0.8 * 10 * 50/100
  EXPECT_DOUBLE_EQ(desired_range_rate(kR, kR, 10.0, p), 0.0);
  EXPECT_DOUBLE_EQ(desired_range_rate(150.0, kR, 10.0, p), 4.0);
  EXPECT_DOUBLE_EQ(desired_range_rate(0.0, kR, 10.0, p), 8.0);  // saturated
}

TEST(TurnRate, OnTheOrbitWithZeroRateItIsTheOrbitRate) {
  const GuidanceParams p;
  EXPECT_DOUBLE_EQ(turn_rate(0.0, 0.0, 10.0, kR, p), 10.0 / kR);
}

TEST(TurnRate, TurnsLeftTowardsTheTargetWhileTheRangeGrowsFasterThanDesired) {
  const GuidanceParams p;
  // Too far (desired -8 m/s) while the range is constant: turn left harder than the orbit.
  const double rdot_des = desired_range_rate(1000.0, kR, 10.0, p);
  EXPECT_GT(turn_rate(0.0, rdot_des, 10.0, kR, p), 10.0 / kR);
  // Closing faster than desired: turn less (or right).
  EXPECT_LT(turn_rate(-9.0, -4.0, 10.0, kR, p), 10.0 / kR);
  EXPECT_DOUBLE_EQ(turn_rate(1.0, -1.0, 10.0, kR, p), 10.0 / kR + 0.02 * 2.0);
}

TEST(TurnRate, SaturatesAtTheTurnLimit) {
  const GuidanceParams p;
  EXPECT_DOUBLE_EQ(turn_rate(10.0, -8.0, 10.0, kR, p), 0.15);    // 0.05 + 0.36
  EXPECT_DOUBLE_EQ(turn_rate(-20.0, 8.0, 10.0, kR, p), -0.15);   // 0.05 - 0.56
}

TEST(SpacingSpeed, FasterWithTheBiggerGapAheadSaturatedCruiseAloneOrEven) {
  const GuidanceParams p;
  EXPECT_DOUBLE_EQ(spacing_speed(Gaps{2.0 * kPi, 2.0 * kPi, 1}, p), 10.0);
  EXPECT_DOUBLE_EQ(spacing_speed(even_gaps(4), p), 10.0);
  // n = 4: (g+ - g-) = 0.2 (2 pi / 4) -> 10 (1 + 0.5 * 0.2) = 11.
  const double quarter = kPi / 2.0;
  EXPECT_NEAR(spacing_speed(Gaps{1.1 * quarter, 0.9 * quarter, 4}, p), 11.0, 1e-12);
  EXPECT_NEAR(spacing_speed(Gaps{0.9 * quarter, 1.1 * quarter, 4}, p), 9.0, 1e-12);
  EXPECT_DOUBLE_EQ(spacing_speed(Gaps{3.0 * quarter, 0.5 * quarter, 4}, p), 13.0);
  EXPECT_DOUBLE_EQ(spacing_speed(Gaps{0.0, 2.0 * kPi, 2}, p), 7.0);
  GuidanceParams off = p;
  off.spacing_gain = 0.0;
  EXPECT_DOUBLE_EQ(spacing_speed(Gaps{3.0 * quarter, 0.5 * quarter, 4}, off), 10.0);
}

TEST(RateLimited, MovesAtMostMaxChangeEitherWay) {
  EXPECT_DOUBLE_EQ(rate_limited(10.0, 13.0, 0.01), 10.01);
  EXPECT_DOUBLE_EQ(rate_limited(10.0, 7.0, 0.01), 9.99);
  EXPECT_DOUBLE_EQ(rate_limited(10.0, 10.005, 0.01), 10.005);
}

TEST(GuidanceLaw, SpeedStartsAtStartSpeedThenRampsAtMaxAccel) {
  EXPECT_EQ(GuidanceLaw{GuidanceParams{}}.speed_mps(), 10.0) << "cruising at the start by default";
  GuidanceParams from_rest;
  from_rest.start_cruising = false;
  GuidanceLaw law{from_rest};
  EXPECT_EQ(law.speed_mps(), 0.0);
  const model::Twist first = law.step(kR, 0.0, kR, even_gaps(4), 0.02);
  EXPECT_DOUBLE_EQ(first.v, 0.01);  // 0.5 m/s^2 * 0.02 s
  EXPECT_DOUBLE_EQ(first.omega, 0.01 / kR);
  for (int k = 1; k < 1000; ++k) {
    law.step(kR, 0.0, kR, even_gaps(4), 0.02);
  }
  EXPECT_NEAR(law.speed_mps(), 10.0, 1e-9);  // 20 s at 0.5 m/s^2
  // A larger gap ahead: 13 m/s asked, reached at 0.5 m/s^2, not at once.
  const model::Twist faster = law.step(kR, 0.0, kR, Gaps{3.0 * kPi / 4.0, kPi / 4.0, 4}, 0.02);
  EXPECT_NEAR(faster.v, 10.01, 1e-9);
  law.reset();
  EXPECT_EQ(law.speed_mps(), 0.0);
}

TEST(GuidanceLaw, BadRadiusOrInputThrowsNamingItAndKeepsTheSpeed) {
  GuidanceLaw law{GuidanceParams{}};
  law.step(kR, 0.0, kR, even_gaps(1), 0.02);
  const double speed = law.speed_mps();
  try {
    law.step(kR, 0.0, 0.0, even_gaps(1), 0.02);
    FAIL() << "radius 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "desired_radius: must be > 0")) << e.what();
  }
  EXPECT_THROW(law.step(kR, 0.0, -5.0, even_gaps(1), 0.02), std::invalid_argument);
  EXPECT_THROW(law.step(std::numeric_limits<double>::quiet_NaN(), 0.0, kR, even_gaps(1), 0.02), std::invalid_argument);
  EXPECT_THROW(law.step(kR, 0.0, kR, even_gaps(1), 0.0), std::invalid_argument);
  EXPECT_EQ(law.speed_mps(), speed);
}

TEST(GuidanceLaw, ConstructorRejectsBadParamsNamingTheKey) {
  GuidanceParams p;
  p.cruise_speed_mps = 0.0;
  try {
    GuidanceLaw law{p};
    FAIL() << "cruise speed 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "cruise_speed_mps: must be > 0")) << e.what();
  }
}

TEST(ObserverBound, DefaultsPass) {
  // V_max = 10 (1 + 0.3) = 13 m/s, 13 * 0.15 = 1.95 <= 2.2.
  EXPECT_EQ(bound_error(13.0, 0.15, 2.2), "");
  EXPECT_NO_THROW(check_observer_bound(GuidanceParams{}, 2.2));
}

TEST(ObserverBound, ATurnLimitOf0p2FailsNamingKeysNumbersAndTheFix) {
  GuidanceParams p;
  p.max_turn_rate_radps = 0.2;
  std::string error;
  try {
    check_observer_bound(p, 2.2, "sta.b");
  } catch (const std::invalid_argument& e) {
    error = e.what();
  }
  // 13 * 0.2 = 2.6 > 2.2
  EXPECT_TRUE(contains(error, "max_turn_rate_radps")) << error;
  EXPECT_TRUE(contains(error, "cruise_speed_mps")) << error;
  EXPECT_TRUE(contains(error, "spacing_saturation")) << error;
  EXPECT_TRUE(contains(error, "13 m/s x 0.2 rad/s = 2.6 m/s^2 > sta.b = 2.2")) << error;
  EXPECT_TRUE(contains(error, "raise sta.b to >= 2.6")) << error;
  EXPECT_TRUE(contains(error, "Lower max_turn_rate_radps to <=")) << error;
  // The key of b is the caller's.
  EXPECT_TRUE(contains(bound_error(13.0, 0.2, 2.2, "observer_accel_bound_mps2"), "> observer_accel_bound_mps2 = 2.2"));
}

}  // namespace
}  // namespace robodds::circumnavigation_controller
