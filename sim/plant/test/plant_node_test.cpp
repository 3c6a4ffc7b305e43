// The plant node on the in-memory bus: plant/cmd in (delay 1), plant/state out.
#include "sim/plant/node/plant_node.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "robodds/idl/robodds.h"
#include "runtime/registry.hpp"
#include "runtime/testing/node_harness.hpp"

ROBODDS_DECLARE_COMPONENT(plant);

namespace robodds::plant {
namespace {

using robodds::testing::NodeHarness;
using robodds::testing::of_instance;

// Steps 0..5 at 100 Hz; robot 2 starts at (5, 0) facing +y.
const char* kScenario = R"(name: plant_node
step_s: 0.01
duration_s: 0.05
seed: 1
robots:
  - {id: 1}
  - {id: 2, x: 5.0, y: 0.0, theta: 1.5707963267948966}
components:
  - {name: plant, type: plant}
)";

void add_plant(NodeHarness& h) {
  robodds::component_registration::register_plant(h.registry());
}

idl::VelocityCommand velocity(std::uint32_t robot, double v, double omega) {
  idl::VelocityCommand cmd;
  cmd.robot_id(robot);
  cmd.mode(idl::VELOCITY);
  cmd.v(v);
  cmd.omega(omega);
  return cmd;
}

TEST(PlantNode, IntegratesTheCommandOfThePreviousStep) {
  NodeHarness h(kScenario);
  add_plant(h);
  // Command of step m: v = 1 + m (robot 1), robot 2 stands still.
  h.feed([&h](std::uint64_t step) {
    h.publish("plant/cmd", velocity(1, 1.0 + static_cast<double>(step), 0.0), step, step + 1);
    h.publish("plant/cmd", velocity(2, 0.0, 0.0), step, step + 1);
  });
  const auto& states = h.record<idl::RobotState>("plant/state");
  h.run({"plant"});

  const auto robot1 = of_instance(states, 1);
  ASSERT_EQ(robot1.size(), 6u);
  double x = 0.0;
  for (std::uint64_t step = 0; step <= 5; ++step) {
    const idl::RobotState& s = robot1[step];
    EXPECT_EQ(s.header().step(), step);
    EXPECT_EQ(s.header().next_step(), step + 1);
    EXPECT_EQ(s.header().stamp_ns(), static_cast<std::int64_t>(step) * 10000000);
    const double applied = step == 0 ? 0.0 : 1.0 + static_cast<double>(step - 1);
    EXPECT_DOUBLE_EQ(s.v(), applied) << "step " << step;
    x += applied * 0.01;
    EXPECT_NEAR(s.x(), x, 1e-12) << "step " << step;
    EXPECT_DOUBLE_EQ(s.y(), 0.0);
  }
  const auto robot2 = of_instance(states, 2);
  ASSERT_EQ(robot2.size(), 6u);
  EXPECT_DOUBLE_EQ(robot2.back().x(), 5.0);
  EXPECT_DOUBLE_EQ(robot2.back().theta(), 1.5707963267948966) << "initial pose from the scenario";
}

TEST(PlantNode, ConvertsWheelSpeedCommands) {
  NodeHarness h(kScenario);
  add_plant(h);
  h.feed([&h](std::uint64_t step) {
    for (std::uint32_t robot : {1u, 2u}) {
      idl::VelocityCommand cmd;
      cmd.robot_id(robot);
      cmd.mode(idl::WHEEL_SPEEDS);
      cmd.v_left(0.5);
      cmd.v_right(1.5);  // wheel base 0.5 m: v = 1 m/s, omega = 2 rad/s
      h.publish("plant/cmd", cmd, step, step + 1);
    }
  });
  const auto& states = h.record<idl::RobotState>("plant/state");
  h.run({"plant"});
  const auto robot1 = of_instance(states, 1);
  ASSERT_EQ(robot1.size(), 6u);
  EXPECT_DOUBLE_EQ(robot1[1].v(), 1.0);
  EXPECT_DOUBLE_EQ(robot1[1].omega(), 2.0);
  EXPECT_NEAR(robot1[5].theta(), 5 * 0.01 * 2.0, 1e-12);
}

TEST(PlantNode, ANonFiniteCommandIsRejectedAndTheLastValidOneKept) {
  NodeHarness h(kScenario);
  add_plant(h);
  h.feed([&h](std::uint64_t step) {
    const double v = step == 2 ? std::numeric_limits<double>::quiet_NaN() : 1.0 + static_cast<double>(step);
    h.publish("plant/cmd", velocity(1, v, 0.0), step, step + 1);
    h.publish("plant/cmd", velocity(2, 0.0, 0.0), step, step + 1);
  });
  const auto& states = h.record<idl::RobotState>("plant/state");
  h.run({"plant"});
  const auto robot1 = of_instance(states, 1);
  ASSERT_EQ(robot1.size(), 6u);
  // Step 3 would integrate the command of step 2 (NaN): the input dropped it, so the plant
  // still applies the command of step 1 (v = 2), not a stop.
  EXPECT_DOUBLE_EQ(robot1[3].v(), 2.0);
  EXPECT_DOUBLE_EQ(robot1[4].v(), 4.0);
  for (const idl::RobotState& s : robot1) {
    EXPECT_TRUE(std::isfinite(s.x()));
  }
}

}  // namespace
}  // namespace robodds::plant
