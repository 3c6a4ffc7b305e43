// The constant-twist commander on the in-memory bus: no inputs, the same plant/cmd for every
// served robot at its rate; its keys are checked by its parameter table.
#include <gtest/gtest.h>

#include <string>

#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_test_scenario.hpp"

ROBODDS_DECLARE_COMPONENT(constant_twist);

namespace robodds::constant_twist {
namespace {

using robodds::testing::of_instance;
using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_constant_twist>;

// Steps 0..20 at 100 Hz; the commander at 10 Hz (steps 0, 10, 20) serves robots 2 and 5.
TEST(ConstantTwistNode, PublishesItsTwistForEveryServedRobotAtItsRate) {
  Harness h(ScenarioText("constant_twist_node", 0.01, 0.2)
                .robots({2, 5})
                .component("{name: commander, type: constant_twist, params: {v_mps: 0.5, omega_radps: -0.2}}"));
  const auto& cmds = h.record<idl::VelocityCommand>("plant/cmd");
  h.run({"commander"});
  for (const std::uint32_t robot : {2u, 5u}) {
    const auto mine = of_instance(cmds, robot);
    ASSERT_EQ(mine.size(), 3u) << "robot " << robot;
    for (std::size_t k = 0; k < mine.size(); ++k) {
      EXPECT_EQ(mine[k].header().step(), 10 * k);
      EXPECT_EQ(mine[k].header().next_step(), 10 * k + 10);
      EXPECT_EQ(mine[k].mode(), idl::VELOCITY);
      EXPECT_DOUBLE_EQ(mine[k].v(), 0.5);
      EXPECT_DOUBLE_EQ(mine[k].omega(), -0.2);
    }
  }
}

TEST(ConstantTwistNode, BadParametersAreConfigErrorsNamingTheKey) {
  for (const auto& [params, key] : {std::pair<std::string, std::string>{"rate_hz: 0", "rate_hz"},
                                    {"rate_hz: 7", "rate_hz"},
                                    {"v_mps: .nan", "v_mps"},
                                    {"omega_radps: fast", "omega_radps"}}) {
    Harness h(ScenarioText("constant_twist_bad", 0.01, 0.1)
                  .robots({1})
                  .component("{name: commander, type: constant_twist, params: {" + params + "}}"));
    const std::string error = h.run_error<ConfigError>({"commander"});
    EXPECT_NE(error.find(key + ":"), std::string::npos) << params << ": " << error;
  }
}

}  // namespace
}  // namespace robodds::constant_twist
