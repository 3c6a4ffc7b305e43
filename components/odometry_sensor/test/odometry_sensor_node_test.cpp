// The odometry sensor node on the in-memory bus: plant/state in, sensor/odometry out at its rate.
#include "components/odometry_sensor/node/odometry_sensor_node.hpp"

#include <gtest/gtest.h>

#include <string>

#include "robodds/idl/robodds.h"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_test_scenario.hpp"

ROBODDS_DECLARE_COMPONENT(odometry_sensor);

namespace robodds::odometry_sensor {
namespace {

using robodds::testing::of_instance;
using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_odometry_sensor>;

// Steps 0..10 at 100 Hz; odometry at 50 Hz (every 2 steps) without noise or slip.
const std::string kScenario =
    ScenarioText("odometry_sensor_node", 0.01, 0.1)
        .robots({3})
        .component("{name: odometry, type: odometry_sensor, params: {wheel_speed_noise_std_mps: 0.0}}");

TEST(OdometrySensorNode, ReportsTheMeanTwistOverEachIntervalStampedAndKeyed) {
  Harness h(kScenario);
  // The plant's state of step m carries the twist applied over step m: v = 1 + m, omega = 0.5.
  h.feed([&h](std::uint64_t step) {
    idl::RobotState s;
    s.robot_id(3);
    s.v(1.0 + static_cast<double>(step));
    s.omega(0.5);
    h.publish("plant/state", s, step, step + 1);
  });
  const auto& readings = h.record<idl::Odometry>("sensor/odometry");
  h.run({"odometry"});

  const auto mine = of_instance(readings, 3);
  ASSERT_EQ(mine.size(), 6u);  // steps 0, 2, ..., 10
  ASSERT_EQ(readings.size(), 6u);
  for (std::size_t i = 1; i < mine.size(); ++i) {
    const std::uint64_t step = 2 * i;
    EXPECT_EQ(mine[i].header().step(), step);
    EXPECT_EQ(mine[i].header().next_step(), step + 2);
    // States of steps step-1 and step: mean v = 1 + step - 0.5, over 2 steps.
    EXPECT_NEAR(mine[i].v(), 0.5 + static_cast<double>(step), 1e-9) << "step " << step;
    EXPECT_NEAR(mine[i].omega(), 0.5, 1e-9);
    EXPECT_NEAR(mine[i].dt_s(), 0.02, 1e-12);
  }
}

}  // namespace
}  // namespace robodds::odometry_sensor
