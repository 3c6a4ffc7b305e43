// The range sensor node on the in-memory bus: ranges to each robot's current target, a new
// instance (robot, target) at a target change, a final sample when the robot leaves, and lost
// samples announced by the previous sample's next_step.
#include "components/range_sensor/node/range_sensor_node.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/io/io.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_test_scenario.hpp"

ROBODDS_DECLARE_COMPONENT(range_sensor);

namespace robodds::range_sensor {
namespace {

using robodds::testing::NodeHarness;
using robodds::testing::of_robot;
using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_range_sensor>;

// Steps 0..10 at 10 Hz; the sensor samples at 5 Hz (every 2 steps), noise-free unless overridden.
std::string scenario(const std::string& params) {
  return ScenarioText("range_sensor_node", 0.1, 1.0)
      .robots({1, 2})
      .component("{name: sensor, type: range_sensor, params: {rate_hz: 5, " + params + "}}");
}

idl::RobotState truth(std::uint32_t robot, std::uint64_t step) {
  idl::RobotState s;
  s.robot_id(robot);
  s.x(static_cast<double>(step));
  s.y(10.0 * robot);
  return s;
}

idl::TargetAssignment task(std::uint32_t robot, bool active, std::uint32_t target, double tx) {
  idl::TargetAssignment a;
  a.robot_id(robot);
  a.active(active);
  a.target_id(target);
  a.target_x(tx);
  a.target_y(0.0);
  a.desired_radius(5.0);
  return a;
}

/// Mission: both robots on target 1 at (0, 0) from step 0; at step `change` robot 1 moves to
/// target 2 at (100, 0) and robot 2 leaves.
void feed(NodeHarness& h, std::uint64_t change) {
  h.feed([&h, change](std::uint64_t step) {
    for (std::uint32_t robot : {1u, 2u}) {
      h.publish("plant/state", truth(robot, step), step, step + 1);
    }
    if (step == 0) {
      h.publish("mission/target", task(1, true, 1, 0.0), 0, change);
      h.publish("mission/target", task(2, true, 1, 0.0), 0, change);
    } else if (step == change) {
      h.publish("mission/target", task(1, true, 2, 100.0), change, kNeverAgain);
      h.publish("mission/target", task(2, false, 0, 0.0), change, kNeverAgain);
    }
  });
}

TEST(RangeSensorNode, RangesToTheCurrentTargetNewInstanceOnAChangeFinalOnLeave) {
  Harness h(scenario("noise_sigma_m: 0"));
  feed(h, 6);
  const auto& ranges = h.record<idl::RangeMeasurement>("sensor/range");
  h.run({"sensor"});

  const auto one = of_robot(ranges, 1);
  ASSERT_EQ(one.size(), 6u);  // steps 0, 2, 4, 6, 8, 10
  for (std::size_t i = 0; i < one.size(); ++i) {
    const std::uint64_t step = 2 * i;
    EXPECT_EQ(one[i].header().step(), step);
    EXPECT_EQ(one[i].header().next_step(), step + 2);
    const bool second_target = step >= 6;
    EXPECT_EQ(one[i].target_id(), second_target ? 2u : 1u) << "step " << step;
    const double tx = second_target ? 100.0 : 0.0;
    EXPECT_DOUBLE_EQ(one[i].range(), std::hypot(static_cast<double>(step) - tx, 10.0)) << "step " << step;
    EXPECT_DOUBLE_EQ(one[i].var(), 0.0);
  }
  const auto two = of_robot(ranges, 2);
  ASSERT_EQ(two.size(), 4u) << "steps 0, 2, 4 and the final sample at the leave (6), nothing after";
  EXPECT_EQ(two.back().header().step(), 6u);
  EXPECT_EQ(two.back().header().next_step(), kNeverAgain);
  EXPECT_EQ(two.back().target_id(), 1u) << "the final sample ends the stream of the old target";
}

// With dropouts every sample announces exactly the step of its robot's next sample, and a
// mission change is published when it happens, lost or not.
TEST(RangeSensorNode, LostSamplesAreAnnouncedAndAChangeIsNeverLost) {
  Harness h(scenario("noise_sigma_m: 0, dropout_probability: 0.6"));
  feed(h, 6);
  const auto& ranges = h.record<idl::RangeMeasurement>("sensor/range");
  h.run({"sensor"});
  const auto one = of_robot(ranges, 1);
  ASSERT_GE(one.size(), 2u);
  EXPECT_LT(one.size(), 6u) << "with p = 0.6 some of the 6 samples are lost (seeded: the same each run)";
  bool change_seen = false;
  for (std::size_t i = 0; i + 1 < one.size(); ++i) {
    EXPECT_EQ(one[i].header().next_step(), one[i + 1].header().step());
    EXPECT_LE(one[i].header().next_step(), 6u > one[i].header().step() ? 6u : kNeverAgain)
        << "a sample before the change announces the change step at the latest";
    change_seen |= one[i + 1].header().step() == 6;
  }
  EXPECT_TRUE(change_seen) << "the target change at step 6 is published";
}

TEST(RangeSensorNode, ARobotWithoutATargetIsAnErrorInLockstep) {
  Harness h(scenario("noise_sigma_m: 0"));
  h.feed([&h](std::uint64_t step) {
    for (std::uint32_t robot : {1u, 2u}) {
      h.publish("plant/state", truth(robot, step), step, step + 1);
    }
    if (step == 0) {
      h.publish("mission/target", task(1, true, 1, 0.0), 0, kNeverAgain);
      h.publish("mission/target", task(2, false, 0, 0.0), 0, kNeverAgain);
    }
  });
  const std::string error = h.run_error<RunError>({"sensor"});
  EXPECT_NE(error.find("robot 2 has no target at step 0"), std::string::npos) << "expected a RunError, got: " << error;
}

}  // namespace
}  // namespace robodds::range_sensor
