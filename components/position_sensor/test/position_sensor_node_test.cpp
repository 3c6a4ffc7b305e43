// The position sensor node on the in-memory bus: plant/state in, sensor/position out at its rate.
#include "components/position_sensor/node/position_sensor_node.hpp"

#include <gtest/gtest.h>

#include <string>

#include "robodds/idl/robodds.h"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_test_scenario.hpp"

ROBODDS_DECLARE_COMPONENT(position_sensor);

namespace robodds::position_sensor {
namespace {

using robodds::testing::of_instance;
using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_position_sensor>;

// Steps 0..25 at 100 Hz; the sensor samples at 10 Hz (steps 0, 10, 20) with a tiny noise.
const std::string kScenario =
    ScenarioText("position_sensor_node", 0.01, 0.25)
        .robots({1, 2})
        .component("{name: sensor, type: position_sensor, params: {noise_var_x_m2: 1.0e-8, noise_var_y_m2: 4.0e-8}}");

idl::RobotState truth(std::uint32_t robot, std::uint64_t step) {
  idl::RobotState s;
  s.robot_id(robot);
  s.x(static_cast<double>(step) * (robot == 1 ? 1.0 : -1.0));
  s.y(10.0 * robot);
  return s;
}

TEST(PositionSensorNode, SamplesTheTruePositionAtItsRateStampedAndKeyed) {
  Harness h(kScenario);
  h.feed([&h](std::uint64_t step) {
    for (std::uint32_t robot : {1u, 2u}) {
      h.publish("plant/state", truth(robot, step), step, step + 1);
    }
  });
  const auto& fixes = h.record<idl::PositionMeasurement>("sensor/position");
  h.run({"sensor"});

  ASSERT_EQ(fixes.size(), 6u);
  for (std::uint32_t robot : {1u, 2u}) {
    const auto mine = of_instance(fixes, robot);
    ASSERT_EQ(mine.size(), 3u) << "robot " << robot;
    for (std::size_t i = 0; i < mine.size(); ++i) {
      const std::uint64_t step = 10 * i;
      EXPECT_EQ(mine[i].header().step(), step);
      EXPECT_EQ(mine[i].header().next_step(), step + 10) << "the next reading is one period later";
      EXPECT_EQ(mine[i].header().stamp_ns(), static_cast<std::int64_t>(step) * 10000000);
      // The state of the same step (delay 0), plus noise of std 1e-4 m.
      EXPECT_NEAR(mine[i].x(), truth(robot, step).x(), 1e-3);
      EXPECT_NEAR(mine[i].y(), truth(robot, step).y(), 1e-3);
      EXPECT_DOUBLE_EQ(mine[i].var_x(), 1.0e-8);
      EXPECT_DOUBLE_EQ(mine[i].var_y(), 4.0e-8);
    }
  }
}

}  // namespace
}  // namespace robodds::position_sensor
