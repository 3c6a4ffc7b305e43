// Issue 27: a steering robot rides through a brief gap of its estimate on its last curvature at
// a reduced speed, for at most hold_s, then stops (both controllers use it).
#include "common/model/estimate_gap_hold.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <stdexcept>

namespace robodds::model {
namespace {

constexpr double kDt = 0.02;       // s: 50 Hz, paper 2's control rate
constexpr double kDecel = 0.5;     // m/s^2: the law's max_accel_mps2
const Twist kOrbit{13.0, 13.0 / 200.0};  // on a 200 m circle at 13 m/s

TEST(EstimateGapHold, KeepsTheCurvatureAndSlowsAtMostMaxDecelForAtMostHoldS) {
  EstimateGapHold hold(HoldParams{1.0, 0.5});
  hold.steered(kOrbit);
  int held = 0;
  double previous_v = kOrbit.v;
  for (int k = 1; k <= 60; ++k) {
    const std::optional<Twist> c = hold.gap(kDt, kDecel);
    if (!c) {
      break;
    }
    ++held;
    EXPECT_NEAR(c->omega / c->v, 1.0 / 200.0, 1e-12) << "the same circle, step " << k;
    EXPECT_NEAR(previous_v - c->v, kDecel * kDt, 1e-12) << "slows at max_decel, step " << k;
    previous_v = c->v;
    EXPECT_TRUE(hold.holding());
  }
  EXPECT_EQ(held, 50) << "1 s at 50 Hz, then stop";
  EXPECT_NEAR(previous_v, 13.0 - 0.5, 1e-9);
  EXPECT_FALSE(hold.holding());
  EXPECT_FALSE(hold.gap(kDt, kDecel).has_value()) << "once run out, it stays stopped until it steers again";
  hold.steered(kOrbit);
  EXPECT_TRUE(hold.gap(kDt, kDecel).has_value()) << "steering again re-arms it";
}

TEST(EstimateGapHold, TheSpeedSettlesAtItsFraction) {
  EstimateGapHold hold(HoldParams{10.0, 0.5});
  hold.steered(kOrbit);
  std::optional<Twist> c;
  for (int k = 0; k < 500; ++k) {  // 10 s: 13 -> 6.5 m/s takes 13 s at 0.5 m/s^2; at 5 m/s^2 1.3 s
    c = hold.gap(kDt, 5.0);
  }
  ASSERT_TRUE(c.has_value());
  EXPECT_DOUBLE_EQ(c->v, 6.5);
  EXPECT_NEAR(c->omega, 6.5 / 200.0, 1e-12);
}

TEST(EstimateGapHold, ARobotThatWasNotSteeringOrNotMovingIsNotHeld) {
  EstimateGapHold hold(HoldParams{});
  EXPECT_FALSE(hold.gap(kDt, kDecel).has_value()) << "never steered";
  hold.steered(kOrbit);
  hold.stopped();
  EXPECT_FALSE(hold.gap(kDt, kDecel).has_value()) << "stopped for another reason before the gap";
  hold.steered(Twist{0.0, 0.1});
  EXPECT_FALSE(hold.gap(kDt, kDecel).has_value()) << "standing: nothing is underway";
}

// Paper 1's robot may have no acceleration limit (0 = none): the reduced speed at once; and the
// way-point law backs up towards a way-point behind (v < 0): held backing up, slower, on the same arc.
TEST(EstimateGapHold, WithoutADecelerationLimitTheReducedSpeedAtOnceAndBackingUpStaysBackingUp) {
  EstimateGapHold hold(HoldParams{1.0, 0.5});
  hold.steered(Twist{-1.2, 3.0});
  const std::optional<Twist> c = hold.gap(0.01, 0.0);
  ASSERT_TRUE(c.has_value());
  EXPECT_DOUBLE_EQ(c->v, -0.6);
  EXPECT_DOUBLE_EQ(c->omega, 1.5) << "the curvature omega / v = -2.5 1/m kept";
}

TEST(EstimateGapHold, ZeroHoldStopsAtOnceAsBefore) {
  EstimateGapHold hold(HoldParams{0.0, 0.5});
  hold.steered(kOrbit);
  EXPECT_FALSE(hold.gap(kDt, kDecel).has_value());
}

TEST(EstimateGapHold, AGapEndsWhenItSteersAgain) {
  EstimateGapHold hold(HoldParams{1.0, 0.5});
  hold.steered(kOrbit);
  for (int k = 0; k < 40; ++k) {
    ASSERT_TRUE(hold.gap(kDt, kDecel).has_value());
  }
  hold.steered(kOrbit);
  EXPECT_EQ(hold.gap_s(), 0.0);
  for (int k = 0; k < 50; ++k) {
    EXPECT_TRUE(hold.gap(kDt, kDecel).has_value()) << "a new gap gets the whole hold_s, step " << k;
  }
}

TEST(EstimateGapHold, BadParamsNameTheKey) {
  EXPECT_THROW(EstimateGapHold(HoldParams{-1.0, 0.5}), std::invalid_argument);
  try {
    EstimateGapHold bad(HoldParams{1.0, 1.5});
    FAIL() << "speed_fraction 1.5 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("speed_fraction: must be in (0, 1]", 0), 0u) << e.what();
  }
  EXPECT_THROW(EstimateGapHold(HoldParams{1.0, 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace robodds::model
