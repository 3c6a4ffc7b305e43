// The circumnavigation controller node on the in-memory bus: observer/range_rate + mission/target +
// estimate/pose (all robots) in, plant/cmd out.
#include "components/circumnavigation_controller/node/circumnavigation_controller_node.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/io/io.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_test_scenario.hpp"

ROBODDS_DECLARE_COMPONENT(circumnavigation_controller);

namespace robodds::circumnavigation_controller {
namespace {

using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_circumnavigation_controller>;

constexpr double kTargetX = 1000.0;
constexpr double kTargetY = 1000.0;
constexpr double kRadius = 200.0;

// Steps 0..5 at 50 Hz; the controller serves robot 1, robot 2 is a peer.
ScenarioText scenario(const std::string& controller_params) {
  return ScenarioText("circumnavigation_controller_node", 0.02, 0.1)
      .robots({1, 2})
      .component("{name: controller, type: circumnavigation_controller, robots: [1], params: {" + controller_params + "}}");
}

idl::TargetAssignment task(std::uint32_t robot, bool active, std::uint32_t target = 1) {
  idl::TargetAssignment a;
  a.robot_id(robot);
  a.active(active);
  a.target_id(target);
  a.target_x(kTargetX);
  a.target_y(kTargetY);
  a.desired_radius(kRadius);
  a.team_size(2);
  a.slot(robot - 1);
  return a;
}

idl::RangeRateEstimate estimate(double range, double range_rate, bool valid, std::uint32_t target = 1) {
  idl::RangeRateEstimate e;
  e.robot_id(1);
  e.target_id(target);
  e.range(range);
  e.range_rate(range_rate);
  e.valid(valid);
  return e;
}

/// A pose at `bearing_deg` seen from the target, on the orbit.
idl::PoseEstimate pose_at(std::uint32_t robot, double bearing_deg) {
  const double b = bearing_deg * 3.14159265358979323846 / 180.0;
  idl::PoseEstimate p;
  p.robot_id(robot);
  p.x(kTargetX + kRadius * std::cos(b));
  p.y(kTargetY + kRadius * std::sin(b));
  p.valid(true);
  return p;
}

struct Feed {
  bool active1 = true;
  bool valid = true;
  double range = kRadius;
  double range_rate = 0.0;
  std::uint32_t target2 = 1;
  double bearing2_deg = 90.0;
  std::uint64_t invalid_step = kNeverAgain;  // the estimate is not valid at this one step
  std::uint64_t invalid_from = kNeverAgain;  // ... and from this step on
};

/// Runs the controller of `scenario_yaml` with missions at step 0 (never again), poses and
/// estimates every step.
std::vector<idl::VelocityCommand> run(const std::string& scenario_yaml, const Feed& f) {
  Harness h(scenario_yaml);
  h.feed([&h, f](std::uint64_t step) {
    if (step == 0) {
      h.publish("mission/target", task(1, f.active1), 0, kNeverAgain);
      h.publish("mission/target", task(2, true, f.target2), 0, kNeverAgain);
    }
    h.publish("estimate/pose", pose_at(1, 0.0), step, step + 1);
    h.publish("estimate/pose", pose_at(2, f.bearing2_deg), step, step + 1);
    h.publish("observer/range_rate", estimate(f.range, f.range_rate, f.valid && step != f.invalid_step && step < f.invalid_from),
                                                  step, step + 1);
  });
  const auto& commands = h.record<idl::VelocityCommand>("plant/cmd");
  h.run({"controller"});
  return commands;
}

TEST(CircumnavigationControllerNode, CommandsZeroOnLeave) {
  Feed f;
  f.active1 = false;
  const auto commands = run(scenario(""), f);
  ASSERT_EQ(commands.size(), 6u) << "a command at every step, also when stopped";
  for (const auto& c : commands) {
    EXPECT_EQ(c.robot_id(), 1u);
    EXPECT_EQ(c.v(), 0.0);
    EXPECT_EQ(c.omega(), 0.0);
  }
}

TEST(CircumnavigationControllerNode, CommandsZeroWhileTheEstimateIsNotValid) {
  Feed f;
  f.valid = false;
  for (const auto& c : run(scenario(""), f)) {
    EXPECT_EQ(c.v(), 0.0);
    EXPECT_EQ(c.omega(), 0.0);
  }
  f.valid = true;  // the same inputs with a valid estimate steer
  const auto commands = run(scenario(""), f);
  ASSERT_EQ(commands.size(), 6u);
  EXPECT_GT(commands.back().v(), 0.0);
}

TEST(CircumnavigationControllerNode, AfterAZeroCommandTheSpeedStartsFromRestAgain) {
  Feed f;
  f.invalid_step = 3;
  const auto commands = run(scenario("start_cruising: false, gap_hold: {hold_s: 0}"), f);
  ASSERT_EQ(commands.size(), 6u);
  EXPECT_NEAR(commands[2].v(), 0.03, 1e-12);
  EXPECT_EQ(commands[3].v(), 0.0);
  EXPECT_NEAR(commands[4].v(), 0.01, 1e-12) << "the robot stood still at step 3: |dV/dt| <= max_accel from rest";
}

// Issue 27: a steering robot whose estimate is invalid for a moment (an observer restart) keeps
// its last curvature, slowing at max_accel, and steers on from that speed when it is valid again.
TEST(CircumnavigationControllerNode, ABriefInvalidEstimateHoldsTheLastCurvatureAtReducedSpeed) {
  Feed f;
  f.invalid_step = 3;
  const auto commands = run(scenario("start_cruising: false"), f);  // gap_hold: its defaults, 1 s at half speed
  ASSERT_EQ(commands.size(), 6u);
  EXPECT_NEAR(commands[2].v(), 0.03, 1e-12);
  EXPECT_NEAR(commands[3].v(), 0.02, 1e-12) << "held: towards half speed at max_accel 0.5 m/s^2";
  ASSERT_NE(commands[2].omega(), 0.0);
  EXPECT_NEAR(commands[3].omega() / commands[3].v(), commands[2].omega() / commands[2].v(), 1e-9) << "the same curvature";
  EXPECT_NEAR(commands[4].v(), 0.03, 1e-12) << "steering again from the held speed, not from rest";
}

TEST(CircumnavigationControllerNode, AGapLongerThanTheHoldStopsTheRobot) {
  Feed f;
  f.invalid_from = 2;
  f.bearing2_deg = 180.0;  // evenly spaced: cruising at V0
  const auto commands = run(scenario("gap_hold: {hold_s: 0.04}"), f);  // 2 steps at 50 Hz
  ASSERT_EQ(commands.size(), 6u);
  EXPECT_EQ(commands[1].v(), 10.0) << "cruising at V0";
  EXPECT_NEAR(commands[2].v(), 9.99, 1e-12) << "held, slowing";
  EXPECT_NEAR(commands[3].v(), 9.98, 1e-12) << "held, slowing";
  EXPECT_EQ(commands[4].v(), 0.0) << "0.06 s > hold_s: stop";
  EXPECT_EQ(commands[4].omega(), 0.0);
  EXPECT_EQ(commands[5].v(), 0.0) << "and stays stopped";
}

TEST(CircumnavigationControllerNode, FarFromTheTargetTurnsTowardsItFromRestAtMaxAccel) {
  Feed far;
  far.range = 1000.0;  // 800 m too far, range constant: turn left harder than the orbit's V / R
  EXPECT_NEAR(run(scenario(""), far).front().v(), 10.0, 0.0101) << "by default the first command cruises (start_cruising), moved by at most max_accel dt";
  const auto commands = run(scenario("start_cruising: false"), far);
  ASSERT_EQ(commands.size(), 6u);
  for (std::size_t k = 0; k < commands.size(); ++k) {
    const double v = 0.01 * static_cast<double>(k + 1);  // 0.5 m/s^2 x 0.02 s per step from rest
    EXPECT_NEAR(commands[k].v(), v, 1e-12);
    // omega = V / R + 0.02 (0 - (-0.8 V))
    EXPECT_NEAR(commands[k].omega(), v / kRadius + 0.02 * 0.8 * v, 1e-12);
    EXPECT_GT(commands[k].omega(), v / kRadius);
  }
  Feed on_orbit;  // on the radius with rate 0: exactly the orbit's turn rate
  const auto orbit = run(scenario(""), on_orbit);
  EXPECT_NEAR(orbit.back().omega(), orbit.back().v() / kRadius, 1e-15);
}

TEST(CircumnavigationControllerNode, SpacesOnlyWithRobotsOfTheSameTarget) {
  // max_accel so large that V reaches the spacing speed at once. Robot 2 is 30 deg ahead of
  // robot 1: gap ahead 30, behind 330 deg -> V = 10 (1 - 0.3) = 7 m/s. On another target it is
  // no team mate: robot 1 alone -> V0 = 10 m/s.
  Feed same;
  same.bearing2_deg = 30.0;
  EXPECT_NEAR(run(scenario("max_accel_mps2: 1000"), same).back().v(), 7.0, 1e-12);
  Feed behind = same;
  behind.bearing2_deg = -30.0;
  EXPECT_NEAR(run(scenario("max_accel_mps2: 1000"), behind).back().v(), 13.0, 1e-12);
  Feed other = same;
  other.target2 = 2;
  EXPECT_NEAR(run(scenario("max_accel_mps2: 1000"), other).back().v(), 10.0, 1e-12);
}

/// Real time: missions at the first step, robot 1's pose every step, robot 2's pose at
/// `bearing2_deg` up to `last_peer_pose`, the observer's estimate on the orbit up to
/// `last_estimate` (then it froze or died).
void feed_realtime(Harness& h, std::uint64_t last_estimate, std::uint64_t last_peer_pose, double bearing2_deg) {
  h.set_mode(TimeMode::kRealtime);
  auto missions_sent = std::make_shared<bool>(false);
  h.feed([&h, missions_sent, last_estimate, last_peer_pose, bearing2_deg](std::uint64_t step) {
    if (!*missions_sent) {
      h.publish("mission/target", task(1, true), step, kNeverAgain);
      h.publish("mission/target", task(2, true), step, kNeverAgain);
      *missions_sent = true;
    }
    h.publish("estimate/pose", pose_at(1, 0.0), step, step + 1);
    if (step <= last_peer_pose) {
      h.publish("estimate/pose", pose_at(2, bearing2_deg), step, step + 1);
    }
    if (step <= last_estimate) {
      h.publish("observer/range_rate", estimate(kRadius, 0.0, true), step, step + 1);
    }
  });
}

// Real time: the observer stops at step 20 (0.4 s), robot 2's pose at step 10 (0.2 s). With
// estimate_timeout_s 0.2 the commands become zero; with peer_timeout_s 0.1 robot 2 drops out of
// the spacing first (robot 1 alone: 10 m/s instead of 7 with robot 2 30 deg ahead).
TEST(CircumnavigationControllerNode, RealTimeStaleEstimateStopsAndStalePeerDropsOut) {
  Harness h(ScenarioText("circumnavigation_controller_stale", 0.02, 1.2)
                .robots({1, 2})
                .component("{name: controller, type: circumnavigation_controller, robots: [1], "
                           "params: {estimate_timeout_s: 0.2, peer_timeout_s: 0.1, max_accel_mps2: 1000}}"));
  constexpr std::uint64_t kLastEstimate = 20;
  constexpr std::uint64_t kLastPeerPose = 10;
  feed_realtime(h, kLastEstimate, kLastPeerPose, 30.0);
  const auto& commands = h.record<idl::VelocityCommand>("plant/cmd");
  h.run({"controller"});
  int spaced = 0;
  int alone = 0;
  int stopped = 0;
  for (const auto& c : commands) {
    const std::uint64_t step = c.header().step();
    if (step <= kLastPeerPose && c.v() > 0.0) {
      ++spaced;
      EXPECT_NEAR(c.v(), 7.0, 1e-9) << "step " << step << ": robot 2 30 deg ahead";
    }
    // 0.1 s limit + 0.1 s margin for a loaded machine.
    if (step >= kLastPeerPose + 10 && step <= kLastEstimate) {
      ++alone;
      EXPECT_NEAR(c.v(), 10.0, 1e-9) << "step " << step << ": robot 2's pose is stale";
    }
    // 0.2 s limit + 0.16 s margin.
    if (step >= kLastEstimate + 18) {
      ++stopped;
      EXPECT_EQ(c.v(), 0.0) << "step " << step << ": estimate silent for " << (step - kLastEstimate) * 0.02 << " s";
      EXPECT_EQ(c.omega(), 0.0) << "step " << step;
    }
  }
  EXPECT_GT(spaced, 0);
  EXPECT_GT(alone, 0);
  EXPECT_GT(stopped, 0);
}

// Issue 24, finding 5: real time, the observer freezes (killed). Until estimate_timeout_s its last
// estimate is no news: the law must not keep ramping on it (it did: +0.01 m/s per step).
TEST(CircumnavigationControllerNode, RealTimeAFrozenEstimateDoesNotRaiseTheCommand) {
  Harness h(ScenarioText("circumnavigation_controller_frozen", 0.02, 1.0)
                .robots({1, 2})
                .component("{name: controller, type: circumnavigation_controller, robots: [1], "
                           "params: {estimate_timeout_s: 0.3, start_cruising: false}}"));
  constexpr std::uint64_t kLastFed = 10;
  feed_realtime(h, kLastFed, kNeverAgain, 90.0);
  const auto& commands = h.record<idl::VelocityCommand>("plant/cmd");
  h.run({"controller"});
  double v_at_last_fed = -1.0;
  double v_max_after = 0.0;
  int stopped = 0;
  for (const auto& c : commands) {
    const std::uint64_t step = c.header().step();
    if (step <= kLastFed) {
      v_at_last_fed = c.v();
    } else {
      v_max_after = std::max(v_max_after, c.v());
      stopped += c.v() == 0.0 && c.omega() == 0.0 ? 1 : 0;
    }
  }
  ASSERT_GT(v_at_last_fed, 0.05) << "the command ramped up from rest while the estimate was fresh";
  // Late after two observer periods (0.04 s): at most 3 more ramp steps of 0.01 m/s, scheduling included.
  EXPECT_LE(v_max_after - v_at_last_fed, 0.03 + 1e-9) << "raised on a frozen estimate from " << v_at_last_fed << " m/s";
  EXPECT_GT(stopped, 0) << "then stale: zero";
}

std::string configure_error(const std::string& scenario_yaml) {
  try {
    run(scenario_yaml, Feed{});
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(CircumnavigationControllerNode, ABrokenObserverBoundIsAConfigureErrorNamingTheKeys) {
  // The scenario declares no bound: the shared fact's default (2.2), said as such.
  const std::string turn = configure_error(scenario("max_turn_rate_radps: 0.2"));
  EXPECT_TRUE(contains(turn, "max_turn_rate_radps")) << turn;
  EXPECT_TRUE(contains(turn, "13 m/s x 0.2 rad/s = 2.6 m/s^2 > facts.range_accel_bound_mps2 (default) = 2.2")) << turn;
  // The bound the scenario declares (a shared fact), named by its file and key.
  const std::string declared = configure_error(scenario("").fact("range_accel_bound_mps2: 1.5"));
  EXPECT_TRUE(contains(declared, ": facts.range_accel_bound_mps2 = 1.5")) << declared;
  // Another component's parameters are not read: an observer's sta.b changes nothing here.
  EXPECT_EQ(configure_error(scenario("").component("{name: observer, type: range_rate_observer, params: {sta: {b: 1.5}}}")), "");
  EXPECT_EQ(configure_error(scenario("")), "");
}

TEST(CircumnavigationControllerNode, BadParamsNameTheKey) {
  EXPECT_TRUE(contains(configure_error(scenario("cruise_speed_mps: 0")), "cruise_speed_mps: must be > 0"));
  EXPECT_TRUE(contains(configure_error(scenario("observer_topic: observer/foo")), "observer_topic"));
}

}  // namespace
}  // namespace robodds::circumnavigation_controller
