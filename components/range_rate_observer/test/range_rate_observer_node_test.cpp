// The range-rate observer node on the in-memory bus: both observers on each robot's range stream,
// a restart (valid false, then valid from the least-squares window) at a target change, final
// estimates when the stream ends, refused samples that leave the state alone, gains checked.
#include "components/range_rate_observer/node/range_rate_observer_node.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "components/range_rate_observer/range_rate_observer.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/io/io.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_test_scenario.hpp"

ROBODDS_DECLARE_COMPONENT(range_rate_observer);

namespace robodds::range_rate_observer {
namespace {

using robodds::testing::NodeHarness;
using robodds::testing::of_robot;
using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_range_rate_observer>;

// 50 Hz, steps 0..200 (4 s); the observer at 50 Hz.
ScenarioText scenario(const std::string& params = "") {
  return ScenarioText("observer_node", 0.02, 4.0)
      .robots({1, 2})
      .component("{name: observer, type: range_rate_observer" + (params.empty() ? std::string() : ", params: {" + params + "}") + "}");
}

constexpr std::uint64_t kSwitchStep = 100;  // 2 s: robot 1 changes target
constexpr std::uint64_t kLeaveStep = 50;    // 1 s: robot 2's stream ends

/// Robot 1: target 1 at 100 + 5 t m until 2 s, then target 2 at 300 - 3 t m. Robot 2: 50 m
/// constant until its final sample at 1 s. `bad_step`: robot 1's range there is `bad_value`.
void feed(NodeHarness& h, std::uint64_t bad_step = 0, double bad_value = 0.0) {
  h.feed([&h, bad_step, bad_value](std::uint64_t step) {
    const double t = static_cast<double>(step) * 0.02;
    idl::RangeMeasurement one;
    one.robot_id(1);
    one.target_id(step < kSwitchStep ? 1 : 2);
    one.range(step < kSwitchStep ? 100.0 + 5.0 * t : 300.0 - 3.0 * t);
    if (bad_step != 0 && step == bad_step) {
      one.range(bad_value);
    }
    h.publish("sensor/range", one, step, step + 1);
    if (step <= kLeaveStep) {
      idl::RangeMeasurement two;
      two.robot_id(2);
      two.target_id(1);
      two.range(50.0);
      h.publish("sensor/range", two, step, step == kLeaveStep ? kNeverAgain : step + 1);
    }
  });
}

TEST(RangeRateObserverNode, EveryObserverRestartsAtATargetChangeAndIsInvalidUntilTheWindowIsFull) {
  Harness h(scenario());
  feed(h);
  const auto& sta = h.record<idl::RangeRateEstimate>("observer/range_rate");
  const auto& linear = h.record<idl::RangeRateEstimate>("observer/range_rate_linear");
  const auto& kalman = h.record<idl::RangeRateEstimate>("observer/range_rate_kf");  // issue 28
  h.run({"observer"});
  for (const auto* topic : {&sta, &linear, &kalman}) {
    const auto one = of_robot(*topic, 1);
    ASSERT_EQ(one.size(), 201u) << "one estimate per step";
    int restarts = 0;
    for (const auto& e : one) {
      const std::uint64_t step = e.header().step();
      EXPECT_EQ(e.target_id(), step < kSwitchStep ? 1u : 2u) << "step " << step;
      restarts += e.restarted() ? 1 : 0;
      EXPECT_EQ(e.restarted(), step == kSwitchStep) << "step " << step;
      // Invalid for the 0.5 s window after the change (steps 100..124), valid otherwise.
      EXPECT_EQ(e.valid(), step < kSwitchStep || step >= kSwitchStep + 25) << "step " << step;
    }
    EXPECT_EQ(restarts, 1);
    // Started from the window's slope: exact on a straight line, at once.
    EXPECT_NEAR(one[kSwitchStep + 25].range_rate(), -3.0, 1e-6);
    EXPECT_NEAR(one.back().range_rate(), -3.0, 0.05);
  }
  // Before the change the super-twisting observer has converged on +5 m/s from rate 0 (2 s),
  // the Kalman filter (a straight line: exact once its acceleration state settles) closer.
  EXPECT_NEAR(of_robot(sta, 1)[kSwitchStep - 1].range_rate(), 5.0, 0.3);
  EXPECT_NEAR(of_robot(kalman, 1)[kSwitchStep - 1].range_rate(), 5.0, 0.3);
}

TEST(RangeRateObserverNode, AnEndedStreamGetsFinalEstimatesAndNothingAfter) {
  Harness h(scenario());
  feed(h);
  const auto& sta = h.record<idl::RangeRateEstimate>("observer/range_rate");
  h.run({"observer"});
  const auto two = of_robot(sta, 2);
  ASSERT_EQ(two.size(), kLeaveStep + 1);
  EXPECT_EQ(two.back().header().next_step(), kNeverAgain);
  EXPECT_EQ(two.front().header().next_step(), 1u);
}

// A NaN or a negative range is refused by the input (counted, docs/architecture.md "Input
// checks"): the observers never see it, their estimate goes on from the good samples.
TEST(RangeRateObserverNode, RefusedRangesLeaveTheObserversAlone) {
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), -20.0}) {
    Harness h(scenario());
    feed(h, 60, bad);
    const auto& sta = h.record<idl::RangeRateEstimate>("observer/range_rate");
    h.run({"observer"});
    const auto one = of_robot(sta, 1);
    ASSERT_EQ(one.size(), 201u);
    for (const auto& e : one) {
      EXPECT_TRUE(std::isfinite(e.range_rate()) && std::isfinite(e.range()));
      EXPECT_EQ(e.restarted(), e.header().step() == kSwitchStep) << "a refused sample is no range jump";
    }
    // Step 60 has no range: it carries the estimate of step 59 predicted to step 60 (issue 27,
    // finding 6), as the library observer fed steps 0-59 predicts it, its std wider.
    SuperTwistingObserver library(SuperTwistingParams{}, {}, 0.02);
    for (std::uint64_t step = 0; step < 60; ++step) {
      const double t = static_cast<double>(step) * 0.02;
      library.update(t, 100.0 + 5.0 * t);
    }
    const RangeRateEstimate predicted = library.predict(1.2);
    EXPECT_NEAR(one[60].range_rate(), predicted.rate_mps, 1e-9);
    EXPECT_NEAR(one[60].range(), predicted.range_m, 1e-9);
    EXPECT_NEAR(one[60].range(), one[59].range() + 0.02 * one[59].range_rate(), 0.01) << "the range moves on";
    EXPECT_GT(one[60].range_rate_std_mps(), one[59].range_rate_std_mps());
    EXPECT_NEAR(one[kSwitchStep - 1].range_rate(), 5.0, 0.3);
  }
}

// Issue 27, finding 6: lost ranges (every third step here, announced by next_step) are gaps the
// observers bridge with their sample period, the sensor's (rate_hz 50: 0.02 s): the node's
// estimates are those of the library observer told that period, not of one integrating each gap
// as one Euler step (sample_period_s 0, which widened the sliding mode's chattering). A lost
// step carries the library observer's prediction to it (RangeRateObserver::predict), not the last
// estimate again.
TEST(RangeRateObserverNode, LostRangesAreBridgedWithTheSensorsSamplePeriod) {
  Harness h(scenario());
  const auto range = [](double t) { return 100.0 + 5.0 * t + 4.0 * std::sin(0.7 * t); };
  const auto lost = [](std::uint64_t step) { return step % 3 == 2; };
  h.feed([&h, &range, &lost](std::uint64_t step) {
    if (step == 0) {
      idl::RangeMeasurement two;  // robot 2: one final sample
      two.robot_id(2);
      two.target_id(1);
      two.range(50.0);
      h.publish("sensor/range", two, step, kNeverAgain);
    }
    if (lost(step)) {
      return;
    }
    idl::RangeMeasurement m;
    m.robot_id(1);
    m.target_id(1);
    m.range(range(static_cast<double>(step) * 0.02));
    h.publish("sensor/range", m, step, lost(step + 1) ? step + 2 : step + 1);
  });
  const auto& sta = h.record<idl::RangeRateEstimate>("observer/range_rate");
  h.run({"observer"});
  const auto one = of_robot(sta, 1);
  ASSERT_EQ(one.size(), 201u) << "a lost step still carries an estimate";
  SuperTwistingObserver bridged(SuperTwistingParams{}, {}, 0.02);
  SuperTwistingObserver euler(SuperTwistingParams{}, {}, 0.0);
  double differs = 0.0;
  double moved = 0.0;  // how far a lost step's prediction is from the last estimate
  for (std::uint64_t step = 0; step <= 200; ++step) {
    if (lost(step)) {
      const double t = static_cast<double>(step) * 0.02;
      const RangeRateEstimate predicted = bridged.predict(t);
      EXPECT_NEAR(one[step].range_rate(), predicted.rate_mps, 1e-9) << "step " << step;
      EXPECT_NEAR(one[step].range(), predicted.range_m, 1e-9) << "step " << step;
      EXPECT_GT(one[step].range_rate_std_mps(), one[step - 1].range_rate_std_mps()) << "step " << step;
      moved = std::max(moved, std::abs(one[step].range() - one[step - 1].range()));
      continue;
    }
    const double t = static_cast<double>(step) * 0.02;
    const double expected = bridged.update(t, range(t)).rate_mps;
    differs = std::max(differs, std::abs(euler.update(t, range(t)).rate_mps - expected));
    EXPECT_NEAR(one[step].range_rate(), expected, 1e-9) << "step " << step;
  }
  EXPECT_GT(differs, 0.01) << "the two ways of integrating a gap must differ for this test to mean anything";
  EXPECT_GT(moved, 0.05) << "the range moves ~0.1 m a step: a republished estimate would not";
}

TEST(RangeRateObserverNode, GainsOutsideThePapersConditionsAreConfigErrorsNamingTheKey) {
  for (const auto& [params, key] : {std::pair<std::string, std::string>{"sta: {a: 2.6}", "sta.a"},
                                    {"sta: {c: -1}", "sta.c"},
                                    {"linear: {k2: 0}", "linear.k2"},
                                    {"sta: {restart_window_s: 0}", "sta.restart_window_s"}}) {
    Harness h(scenario(params));
    const std::string error = h.run_error<ConfigError>({"observer"});
    EXPECT_NE(error.find(key + ":"), std::string::npos) << params << ": expected a ConfigError, got: " << error;
  }
}

// Issue 27: the restart window must span at least two range sample periods (the observer's rate
// is the sensor's), or the restarted rate rests on one difference of two noisy ranges.
TEST(RangeRateObserverNode, ARestartWindowShorterThanTwoSamplePeriodsIsAConfigError) {
  {
    Harness h(scenario("rate_hz: 2, sta: {restart_window_s: 0.5}"));  // 0.5 s periods: the window holds 2 samples
    const std::string error = h.run_error<ConfigError>({"observer"});
    EXPECT_NE(error.find("sta.restart_window_s: 0.5 s spans fewer than two periods of the range samples (0.5 s at rate_hz 2): "
                         "the restarted rate would rest on one difference of two noisy ranges; make it at least 1 s"),
              std::string::npos)
        << error;
  }
  {
    Harness h(scenario("rate_hz: 2, sta: {restart_window_s: 1}, linear: {restart_window_s: 0.9}"));
    EXPECT_NE(h.run_error<ConfigError>({"observer"}).find("linear.restart_window_s: 0.9 s spans"), std::string::npos);
  }
  Harness h(scenario("rate_hz: 5"));  // 0.2 s periods: the default 0.5 s window holds 3 samples
  feed(h);
  EXPECT_EQ(h.run_error<ConfigError>({"observer"}), "");
}

// b must cover the range accelerations the mission allows: the scenario's shared fact
// range_accel_bound_mps2 (default 2.2), never another component's parameter.
TEST(RangeRateObserverNode, AGainBBelowTheScenariosRangeAccelerationBoundIsAConfigError) {
  {
    Harness h(scenario("sta: {b: 2.0}"));  // below the default bound
    const std::string error = h.run_error<ConfigError>({"observer"});
    EXPECT_NE(error.find("sta.b: 2 m/s^2 is below the range acceleration bound 2.2 m/s^2 of facts.range_accel_bound_mps2 (default)"),
              std::string::npos)
        << error;
  }
  {
    Harness h(scenario("sta: {b: 2.5}").fact("range_accel_bound_mps2: 3.0"));  // a declared bound above b
    const std::string error = h.run_error<ConfigError>({"observer"});
    EXPECT_NE(error.find(": facts.range_accel_bound_mps2: the observer would not follow"), std::string::npos) << error;
  }
  Harness h(scenario("sta: {b: 2.0}").fact("range_accel_bound_mps2: 1.5"));  // b covers it: runs
  feed(h);
  h.run({"observer"});
}

}  // namespace
}  // namespace robodds::range_rate_observer
