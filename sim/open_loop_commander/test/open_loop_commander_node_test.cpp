// The open-loop commander node on the in-memory bus: no inputs, plant/cmd out at its rate.
#include "sim/open_loop_commander/node/open_loop_commander_node.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "robodds/idl/robodds.h"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_test_scenario.hpp"
#include "sim/open_loop_commander/open_loop_commander.hpp"

ROBODDS_DECLARE_COMPONENT(open_loop_commander);

namespace robodds::open_loop_commander {
namespace {

using robodds::testing::of_instance;
using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_open_loop_commander>;

// Steps 0..10 at 100 Hz; commands at 50 Hz; v is NaN at step 4 (fault injection).
const std::string kScenario =
    ScenarioText("open_loop_node", 0.01, 0.1)
        .robots({4, 7})
        .component("{name: commander, type: open_loop_commander, params: {v_mps: 2.0, omega_period_s: 0.1, inject_nan_at_step: 4}}");

TEST(OpenLoopNode, PublishesTheCommanderLawPerRobotAtItsRate) {
  Harness h(kScenario);
  const auto& commands = h.record<idl::VelocityCommand>("plant/cmd");
  h.run({"commander"});

  OpenLoopParams law;  // the defaults file's values with the scenario's overrides
  law.v_mps = 2.0;
  law.omega_period_s = 0.1;
  ASSERT_EQ(commands.size(), 12u);  // 2 robots x steps 0, 2, ..., 10
  const std::uint32_t robots[] = {4, 7};
  for (std::size_t index = 0; index < 2; ++index) {
    const auto mine = of_instance(commands, robots[index]);
    ASSERT_EQ(mine.size(), 6u);
    for (std::size_t i = 0; i < mine.size(); ++i) {
      const std::uint64_t step = 2 * i;
      const TwistCommand expected = open_loop_command(law, index, static_cast<double>(step) * 0.01);
      EXPECT_EQ(mine[i].header().step(), step);
      EXPECT_EQ(mine[i].header().next_step(), step + 2);
      EXPECT_EQ(mine[i].mode(), idl::VELOCITY);
      EXPECT_DOUBLE_EQ(mine[i].omega(), expected.omega) << "robot " << robots[index] << " step " << step;
      if (step == 4) {
        EXPECT_TRUE(std::isnan(mine[i].v())) << "inject_nan_at_step";
      } else {
        EXPECT_DOUBLE_EQ(mine[i].v(), 2.0);
      }
    }
  }
  // Robots get different phases: their turn rates differ.
  EXPECT_NE(of_instance(commands, 4)[1].omega(), of_instance(commands, 7)[1].omega());
}

}  // namespace
}  // namespace robodds::open_loop_commander
