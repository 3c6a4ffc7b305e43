// The route follower node on the in-memory bus: estimate/pose in, plant/cmd (VELOCITY) out at
// every control step; a turn in place, then straight driving; zero on an invalid or (real time)
// stale estimate; a bad route is a start-up error naming the key.
#include "components/route_follower/node/route_follower_node.hpp"

#include <gtest/gtest.h>

#include <string>

#include "common/angle.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/io/io.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_test_scenario.hpp"

ROBODDS_DECLARE_COMPONENT(route_follower);

namespace robodds::route_follower {
namespace {

using robodds::testing::of_robot;
using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_route_follower>;

// Steps 0..10 at 50 Hz (the default control rate); robot 2 drives the open path (0,0) -> (2,0).
const std::string kScenario =
    ScenarioText("route_follower_node", 0.02, 0.2)
        .robots({1, 2})
        .component("{name: follower, type: route_follower, robots: [2], params: {route: [[0, 0], [2, 0]], loop: false}}");

idl::PoseEstimate estimate(std::uint32_t robot, double x, double theta, bool valid) {
  idl::PoseEstimate e;
  e.robot_id(robot);
  e.x(x);
  e.theta(theta);
  e.valid(valid);
  return e;
}

TEST(RouteFollowerNode, TurnsInPlaceThenDrivesStraight) {
  Harness h(kScenario);
  // On vertex 0 facing north (vertex 1 is east) until step 4, then facing east and moving on.
  h.feed([&h](std::uint64_t step) {
    const bool turned = step >= 5;
    h.publish("estimate/pose", estimate(2, turned ? 0.02 * static_cast<double>(step - 4) : 0.0, turned ? 0.0 : kPi / 2, true),
              step, step + 1);
  });
  const auto& commands = h.record<idl::VelocityCommand>("plant/cmd");
  h.run({"follower"});
  ASSERT_EQ(commands.size(), 11u) << "a command at every step, for the served robot only";
  EXPECT_TRUE(of_robot(commands, 1).empty()) << "robot 1 is not served by this instance";
  for (std::size_t i = 0; i < commands.size(); ++i) {
    const idl::VelocityCommand& cmd = commands[i];
    EXPECT_EQ(cmd.header().step(), i);
    EXPECT_EQ(cmd.header().next_step(), i + 1);
    EXPECT_EQ(cmd.robot_id(), 2u);
    EXPECT_EQ(cmd.mode(), idl::VELOCITY);
    if (i < 5) {
      EXPECT_EQ(cmd.v(), 0.0) << "step " << i << ": turning in place";
      EXPECT_DOUBLE_EQ(cmd.omega(), -0.5) << "step " << i << ": right, at the turn rate";
    } else {
      EXPECT_DOUBLE_EQ(cmd.v(), 0.2) << "step " << i << ": driving";
      EXPECT_DOUBLE_EQ(cmd.omega(), 0.0) << "step " << i << ": on the segment";
    }
  }
}

TEST(RouteFollowerNode, ZeroCommandWhileTheEstimateIsNotValid) {
  Harness h(kScenario);
  h.feed([&h](std::uint64_t step) {
    h.publish("estimate/pose", estimate(2, 0.0, kPi / 2, step >= 6), step, step + 1);
  });
  const auto& commands = h.record<idl::VelocityCommand>("plant/cmd");
  h.run({"follower"});
  ASSERT_EQ(commands.size(), 11u);
  for (std::size_t i = 0; i < commands.size(); ++i) {
    EXPECT_EQ(commands[i].v(), 0.0) << "step " << i;
    if (i < 6) {
      EXPECT_EQ(commands[i].omega(), 0.0) << "step " << i << ": estimate not valid";
    } else {
      EXPECT_DOUBLE_EQ(commands[i].omega(), -0.5) << "step " << i << ": valid: the turn starts";
    }
  }
}

// Real time: when the estimates stop arriving, the commands are zero within estimate_timeout_s
// of the last receipt (this process's receive time), instead of steering on the frozen estimate.
TEST(RouteFollowerNode, RealTimeStaleEstimateStopsTheRobot) {
  Harness h(ScenarioText("route_follower_stale", 0.02, 0.8)
                .robots({1})
                .component("{name: follower, type: route_follower, params: {route: [[0, 0], [10, 0]], estimate_timeout_s: 0.2}}"));
  h.set_mode(TimeMode::kRealtime);
  constexpr std::uint64_t kLastFed = 15;  // the estimator dies after 0.3 s
  h.feed([&h](std::uint64_t step) {
    if (step <= kLastFed) {
      h.publish("estimate/pose", estimate(1, 0.0, 0.0, true), step, step + 1);
    }
  });
  const auto& commands = h.record<idl::VelocityCommand>("plant/cmd");
  h.run({"follower"});
  int driving = 0;
  int stopped = 0;
  for (const idl::VelocityCommand& cmd : commands) {
    const std::uint64_t step = cmd.header().step();
    if (step <= kLastFed && cmd.v() > 0.0) {
      ++driving;
    }
    if (step >= kLastFed + 18) {  // 0.2 s limit + 0.16 s margin for a loaded machine
      ++stopped;
      EXPECT_EQ(cmd.v(), 0.0) << "step " << step << ": estimate silent for " << (step - kLastFed) * 0.02 << " s";
      EXPECT_EQ(cmd.omega(), 0.0) << "step " << step;
    }
  }
  EXPECT_GT(driving, 0) << "the follower drove while the estimate was fresh";
  EXPECT_GT(stopped, 0);
}

TEST(RouteFollowerNode, ABadRouteIsAStartUpErrorNamingTheKey) {
  Harness h(ScenarioText("bad_route", 0.02, 0.1)
                .robots({1})
                .component("{name: follower, type: route_follower, params: {route: [[0, 0], [0.01, 0]]}}"));
  const std::string error = h.run_error<ConfigError>({"follower"});
  EXPECT_NE(error.find("route: consecutive points must be at least position_tolerance_m 0.05 m apart"), std::string::npos)
      << "points 1 cm apart (tolerance 5 cm) must be a ConfigError, got: " << error;
}

}  // namespace
}  // namespace robodds::route_follower
