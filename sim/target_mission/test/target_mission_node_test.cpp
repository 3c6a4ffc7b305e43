// The target mission node on the in-memory bus: each robot's task at step 0 and at every event
// step, each sample announcing the next (next_step), the last one final.
#include "sim/target_mission/node/target_mission_node.hpp"

#include <gtest/gtest.h>

#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/io/io.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_harness.hpp"

ROBODDS_DECLARE_COMPONENT(target_mission);

namespace robodds::target_mission {
namespace {

using robodds::testing::NodeHarness;

const char* kScenario = R"(name: target_mission
step_s: 0.5
duration_s: 3.0
seed: 1
robots:
  - {id: 1}
  - {id: 2}
  - {id: 3}
components:
  - {name: mission, type: target_mission}
targets:
  - {id: 1, x: 10, y: 20, radius_m: 5}
  - {id: 2, x: 30, y: 40, radius_m: 6}
events:
  - {time_s: 0, robots: [1, 2], target: 1}
  - {time_s: 1.0, robots: [1], target: 2}
  - {time_s: 1.0, robots: [2], leave: true}
)";

TEST(TargetMissionNode, PublishesTasksAtEachEventStepAnnouncingTheNext) {
  NodeHarness h(kScenario);
  robodds::component_registration::register_target_mission(h.registry());
  const auto& tasks = h.record<idl::TargetAssignment>("mission/target");
  h.run({"mission"});
  ASSERT_EQ(tasks.size(), 6u) << "3 robots x 2 event steps (0 and 2), not every step";
  // Step 0: robots 1 and 2 on target 1 (team of 2), robot 3 without a task; next at step 2.
  EXPECT_TRUE(tasks[0].active());
  EXPECT_EQ(tasks[1].slot(), 1u);
  EXPECT_EQ(tasks[1].team_size(), 2u);
  EXPECT_FALSE(tasks[2].active());
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(tasks[i].header().step(), 0u);
    EXPECT_EQ(tasks[i].header().next_step(), 2u);
  }
  // Step 2 (1.0 s): robot 1 on target 2 alone, robot 2 left; final.
  EXPECT_EQ(tasks[3].target_id(), 2u);
  EXPECT_DOUBLE_EQ(tasks[3].target_x(), 30.0);
  EXPECT_DOUBLE_EQ(tasks[3].desired_radius(), 6.0);
  EXPECT_EQ(tasks[3].team_size(), 1u);
  EXPECT_FALSE(tasks[4].active());
  for (std::size_t i = 3; i < 6; ++i) {
    EXPECT_EQ(tasks[i].header().step(), 2u);
    EXPECT_EQ(tasks[i].header().next_step(), kNeverAgain);
  }
}

TEST(TargetMissionNode, AScenarioWithoutEventsIsAConfigError) {
  const std::string no_events = std::string(kScenario).substr(0, std::string(kScenario).find("targets:"));
  NodeHarness h(no_events);
  robodds::component_registration::register_target_mission(h.registry());
  const std::string error = h.run_error<ConfigError>({"mission"});
  EXPECT_NE(error.find("needs the scenario's 'targets:' and 'events:'"), std::string::npos)
      << "expected a ConfigError, got: " << error;
}

}  // namespace
}  // namespace robodds::target_mission
