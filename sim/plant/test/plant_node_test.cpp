// The plant node on the in-memory bus: plant/cmd in (delay 1), plant/state out.
#include "sim/plant/node/plant_node.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/io/sample_checks.hpp"
#include "runtime/testing/node_test_scenario.hpp"

ROBODDS_DECLARE_COMPONENT(plant);

namespace robodds::plant {
namespace {

using robodds::testing::of_instance;
using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_plant>;

// Steps 0..5 at 100 Hz; robot 2 starts at (5, 0) facing +y.
const std::string kScenario = ScenarioText("plant_node", 0.01, 0.05)
                                  .robots({1})
                                  .robot("{id: 2, x: 5.0, y: 0.0, theta: 1.5707963267948966}")
                                  .component("{name: plant, type: plant}");

idl::VelocityCommand velocity(std::uint32_t robot, double v, double omega) {
  idl::VelocityCommand cmd;
  cmd.robot_id(robot);
  cmd.mode(idl::VELOCITY);
  cmd.v(v);
  cmd.omega(omega);
  return cmd;
}

TEST(PlantNode, IntegratesTheCommandOfThePreviousStep) {
  Harness h(kScenario);
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
  Harness h(kScenario);
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
  Harness h(kScenario);
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

// Finding 3 of issue 9: a command beyond the gross bounds or with a mode outside CommandMode is
// refused by the input (runtime/io/sample_checks.hpp) and never integrated; the last valid one is kept.
TEST(PlantNode, AbsurdCommandsAndBadModesAreRefusedNotIntegrated) {
  Harness h(kScenario);
  h.feed([&h](std::uint64_t step) {
    idl::VelocityCommand one = velocity(1, step == 2 ? 1e300 : 1.0, 0.0);
    h.publish("plant/cmd", one, step, step + 1);
    idl::VelocityCommand two = velocity(2, step == 0 ? 0.5 : 1.0, 0.0);
    if (step >= 1) {
      two.mode(static_cast<idl::CommandMode>(7));  // not a CommandMode
    }
    h.publish("plant/cmd", two, step, step + 1);
  });
  const auto& states = h.record<idl::RobotState>("plant/state");
  h.run({"plant"});
  const auto robot1 = of_instance(states, 1);
  ASSERT_EQ(robot1.size(), 6u);
  EXPECT_DOUBLE_EQ(robot1[3].v(), 1.0) << "the command of step 2 (v = 1e300) was refused; step 1's is kept";
  EXPECT_NEAR(robot1.back().x(), 0.05, 1e-12);
  const auto robot2 = of_instance(states, 2);
  ASSERT_EQ(robot2.size(), 6u);
  for (std::size_t step = 1; step < robot2.size(); ++step) {
    EXPECT_DOUBLE_EQ(robot2[step].v(), 0.5) << "step " << step << ": mode 7 was refused, the VELOCITY command of step 0 kept";
  }
}

TEST(PlantNode, CommandsBeyondTheLimitsAreSaturated) {
  Harness h(ScenarioText("plant_limits", 0.01, 0.05)
                .fact("robot_body: {max_speed_mps: 1.0, max_turn_rate_radps: 0.5}")
                .robots({1})
                .robot("{id: 2, facts: {robot_body: {max_speed_mps: 2.0}}}")
                .component("{name: plant, type: plant}"));
  h.feed([&h](std::uint64_t step) {
    h.publish("plant/cmd", velocity(1, -5.0, 2.0), step, step + 1);
    h.publish("plant/cmd", velocity(2, -5.0, 2.0), step, step + 1);
  });
  const auto& states = h.record<idl::RobotState>("plant/state");
  h.run({"plant"});
  const auto robot1 = of_instance(states, 1);
  ASSERT_EQ(robot1.size(), 6u);
  EXPECT_DOUBLE_EQ(robot1[3].v(), -1.0);
  EXPECT_DOUBLE_EQ(robot1[3].omega(), 0.5);
  const auto robot2 = of_instance(states, 2);  // its own body: 2 m/s, the scenario's 0.5 rad/s
  ASSERT_EQ(robot2.size(), 6u);
  EXPECT_DOUBLE_EQ(robot2[3].v(), -2.0);
  EXPECT_DOUBLE_EQ(robot2[3].omega(), 0.5);
}

// Actuator model: wheel base 0.3 m, wheels at most 1.5 m/s each (clamped one by one), 1 m/s^2,
// 5 rad/s^2. A command of (18 m/s, 60 rad/s) is wheels (9, 27): clamped to (1.5, 1.5), i.e. a
// straight line at 1.5 m/s, reached at 1 m/s^2.
TEST(PlantNode, WheelSpeedsAreClampedAndTheTwistRampsAtTheAccelerationLimits) {
  Harness h(ScenarioText("plant_actuator", 0.01, 2.0)
                .fact("robot_body: {wheel_base_m: 0.3, max_wheel_speed_mps: 1.5, max_accel_mps2: 1.0, max_angular_accel_radps2: 5.0}")
                .robots({1})
                .component("{name: plant, type: plant}"));
  h.feed([&h](std::uint64_t step) {
    h.publish("plant/cmd", step < 100 ? velocity(1, 18.0, 60.0) : velocity(1, 0.0, -60.0), step, step + 1);
  });
  const auto& states = h.record<idl::RobotState>("plant/state");
  h.run({"plant"});
  ASSERT_EQ(states.size(), 201u);
  for (std::size_t k = 1; k < states.size(); ++k) {
    const double v = states[k].v();
    const double omega = states[k].omega();
    EXPECT_LE(std::abs(v - 0.15 * omega), 1.5 + 1e-12) << "left wheel, step " << k;
    EXPECT_LE(std::abs(v + 0.15 * omega), 1.5 + 1e-12) << "right wheel, step " << k;
    EXPECT_LE(std::abs(v - states[k - 1].v()), 0.01 + 1e-12) << "step " << k;
    EXPECT_LE(std::abs(omega - states[k - 1].omega()), 0.05 + 1e-12) << "step " << k;
  }
  EXPECT_NEAR(states[50].v(), 0.5, 1e-12) << "step 50: 50 steps of 0.01 m/s (step 1 applies the command of step 0)";
  EXPECT_DOUBLE_EQ(states[50].omega(), 0.0) << "both wheels clamped to 1.5: straight";
  // From step 101 on: (0, -60) is wheels (9, -9), clamped to (1.5, -1.5): omega = -10 rad/s,
  // v = 0; the change is scaled as one: omega ramps at 5 rad/s^2 and v falls by the same fraction.
  EXPECT_NEAR(states[100].v(), 1.0, 1e-12);
  EXPECT_NEAR(states[110].omega(), -0.5, 1e-9);
  EXPECT_LT(states[110].v(), states[100].v());
  EXPECT_GT(states[110].v(), 0.0) << "v falls no faster than 1 m/s^2";
  EXPECT_NEAR(states[110].v(), 0.95, 1e-9) << "on the segment from (1, 0) to (0, -10)";
}

// Kidnapped robot: at t = 0.03 s (step 3) the true pose jumps once by (10, -2) m and pi/2 rad,
// on top of the motion; the applied twist is unchanged.
TEST(PlantNode, TheDisturbanceMovesThePoseOnceAtItsTime) {
  Harness h(ScenarioText("plant_disturbance", 0.01, 0.05)
                .robots({1})
                .component("{name: plant, type: plant, params: {disturbance_at_s: 0.03, disturbance_dx_m: 10.0, disturbance_dy_m: -2.0, "
                           "disturbance_dtheta_rad: 1.5707963267948966}}"));
  h.feed([&h](std::uint64_t step) { h.publish("plant/cmd", velocity(1, 1.0, 0.0), step, step + 1); });
  const auto& states = h.record<idl::RobotState>("plant/state");
  h.run({"plant"});
  ASSERT_EQ(states.size(), 6u);
  EXPECT_NEAR(states[2].x(), 0.02, 1e-12) << "before the jump: driven along +x";
  EXPECT_DOUBLE_EQ(states[2].theta(), 0.0);
  EXPECT_NEAR(states[3].x(), 10.03, 1e-12) << "step 3: moved 0.01 m, then jumped 10 m";
  EXPECT_NEAR(states[3].y(), -2.0, 1e-12);
  EXPECT_NEAR(states[3].theta(), 1.5707963267948966, 1e-12);
  EXPECT_DOUBLE_EQ(states[3].v(), 1.0) << "the jump is no motion: the applied twist is the command's";
  EXPECT_NEAR(states[5].x(), 10.03, 1e-12) << "once only: afterwards the robot drives on along its new heading (+y)";
  EXPECT_NEAR(states[5].y(), -1.98, 1e-12);
}

// Real time, scenario of 0.6 s with a 0.2 s command timeout.
const std::string kRealTimeScenario = ScenarioText("plant_realtime", 0.01, 0.6)
                                          .robots({1, 2})
                                          .component("{name: plant, type: plant, params: {command_timeout_s: 0.2}}");
constexpr std::uint64_t kLastCommand = 20;  // the commander stops after 0.2 s
constexpr std::uint64_t kStoppedFrom = kLastCommand + 20 + 15;  // + timeout + margin for a loaded machine

// Finding 2 of issue 9: a command stamped in the future (or negative) never expired. It is now
// refused on arrival (stamp_in_future, negative_stamp), so the robot never moves on it.
TEST(PlantNode, RealTimeCommandsWithAbsurdStampsAreRefused) {
  Harness h(kRealTimeScenario);
  h.set_mode(TimeMode::kRealtime);
  h.feed([&h](std::uint64_t step) {
    if (step <= kLastCommand) {
      h.publish_stamped("plant/cmd", velocity(1, 1.0, 0.0), step, step + 1, std::numeric_limits<std::int64_t>::max());
      h.publish_stamped("plant/cmd", velocity(2, 1.0, 0.0), step, step + 1, std::numeric_limits<std::int64_t>::min());
    }
  });
  const auto& states = h.record<idl::RobotState>("plant/state");
  h.run({"plant"});
  ASSERT_FALSE(states.empty());
  for (const idl::RobotState& s : states) {
    EXPECT_DOUBLE_EQ(s.v(), 0.0) << "robot " << s.robot_id() << " step " << s.header().step();
    EXPECT_TRUE(std::isfinite(s.x()));
  }
}

// Finding 1/2 of issue 9: a command's age is its receive time on this process's clock; a sender
// whose clock is 10 s behind still drives the robot, and the robot stops within the timeout of
// the last receipt.
TEST(PlantNode, RealTimeCommandAgeIsJudgedByReceiveTimeNotTheSendersClock) {
  Harness h(kRealTimeScenario);
  h.set_mode(TimeMode::kRealtime);
  h.feed([&h](std::uint64_t step) {
    if (step <= kLastCommand) {
      const std::int64_t behind = wall_clock_now_ns() - 10'000'000'000;
      h.publish_stamped("plant/cmd", velocity(1, 1.0, 0.0), step, step + 1, behind);
      h.publish("plant/cmd", velocity(2, 1.0, 0.0), step, step + 1);
    }
  });
  const auto& states = h.record<idl::RobotState>("plant/state");
  h.run({"plant"});
  for (std::uint32_t robot : {1u, 2u}) {
    int driven = 0;
    int stopped = 0;
    for (const idl::RobotState& s : of_instance(states, robot)) {
      const std::uint64_t step = s.header().step();
      if (step >= 2 && step <= kLastCommand) {
        driven += s.v() == 1.0 ? 1 : 0;
      }
      if (step >= kStoppedFrom) {
        ++stopped;
        EXPECT_DOUBLE_EQ(s.v(), 0.0) << "robot " << robot << " step " << step << ": no command for " << (step - kLastCommand) * 0.01 << " s";
      }
    }
    EXPECT_GT(driven, 0) << "robot " << robot << " was never driven by its fresh commands";
    EXPECT_GT(stopped, 0) << "robot " << robot;
  }
}

// With acceleration limits a stale command still stops the robot at once (a motor driver's
// watchdog), not at max_accel_mps2: the limits shape commands, not the safe stop.
TEST(PlantNode, RealTimeStaleCommandStopsAtOnceDespiteAccelerationLimits) {
  Harness h(ScenarioText("plant_realtime_limits", 0.01, 0.6)
                .fact("robot_body: {max_accel_mps2: 0.5, max_angular_accel_radps2: 0.5}")
                .robots({1})
                .component("{name: plant, type: plant, params: {command_timeout_s: 0.2}}"));
  h.set_mode(TimeMode::kRealtime);
  h.feed([&h](std::uint64_t step) {
    if (step <= kLastCommand) {
      h.publish("plant/cmd", velocity(1, 1.0, 0.0), step, step + 1);
    }
  });
  const auto& states = h.record<idl::RobotState>("plant/state");
  h.run({"plant"});
  double fastest = 0.0;
  int stopped = 0;
  for (const idl::RobotState& s : states) {
    fastest = std::max(fastest, s.v());
    if (s.header().step() >= kStoppedFrom) {
      ++stopped;
      EXPECT_DOUBLE_EQ(s.v(), 0.0) << "step " << s.header().step();
    }
  }
  EXPECT_GT(fastest, 0.02) << "the robot ramped up on its fresh commands";
  EXPECT_LT(fastest, 0.5) << "at most 0.5 m/s^2 for the 0.2 s of commands";
  EXPECT_GT(stopped, 0);
}

// A command held up on its way (queued in the sender's kernel while a cable was cut, delivered
// when the link returned: integration.netns_link_cut) is just received but seconds old. The
// plant measures the hold-up against the fastest delay of that robot's commands, so the clocks'
// offset cancels out, and adds it to the receive age: robot 1's late command is never applied;
// robot 2's command of the same step, not held up, is.
TEST(PlantNode, RealTimeCommandHeldUpOnTheWayIsStale) {
  Harness h(kRealTimeScenario);
  h.set_mode(TimeMode::kRealtime);
  constexpr std::uint64_t kLate = 40;  // the link is back: a 1 s old command arrives
  h.feed([&h](std::uint64_t step) {
    if (step <= 10) {
      h.publish("plant/cmd", velocity(1, 1.0, 0.0), step, step + 1);
      h.publish("plant/cmd", velocity(2, 1.0, 0.0), step, step + 1);
    }
    if (step == kLate) {
      h.publish_stamped("plant/cmd", velocity(1, 0.5, 0.0), step, step + 1, wall_clock_now_ns() - 1'000'000'000);
      h.publish("plant/cmd", velocity(2, 0.5, 0.0), step, step + 1);
    }
  });
  const auto& states = h.record<idl::RobotState>("plant/state");
  h.run({"plant"});
  int late_applied = 0;
  int fresh_applied = 0;
  for (const idl::RobotState& s : states) {
    if (s.header().step() > kLate) {
      (s.robot_id() == 1 ? late_applied : fresh_applied) += s.v() == 0.5 ? 1 : 0;
    }
  }
  EXPECT_EQ(late_applied, 0) << "robot 1 moved on a command held up for 1 s";
  EXPECT_GT(fresh_applied, 0) << "robot 2 never moved on its fresh command";
}

TEST(PlantNode, CommandTimeoutMustExceedThePlantPeriod) {
  Harness h(ScenarioText("bad_timeout", 0.01, 0.05)
                .robots({1})
                .component("{name: plant, type: plant, params: {command_timeout_s: 0.01}}"));
  const std::string error = h.run_error<ConfigError>({"plant"});
  EXPECT_NE(error.find("command_timeout_s: must be longer than the component's period"), std::string::npos)
      << "a timeout not longer than the plant's period must be a ConfigError, got: " << error;
}

}  // namespace
}  // namespace robodds::plant
