// The mission source node on the in-memory bus: publishes each robot's way-points once, final
// (next_step = never) on the transient-local mission topic.
#include "sim/mission_source/node/mission_source_node.hpp"

#include <gtest/gtest.h>

#include "robodds/idl/robodds.h"
#include "runtime/error.hpp"
#include "runtime/io.hpp"
#include "runtime/registry.hpp"
#include "runtime/testing/node_harness.hpp"

ROBODDS_DECLARE_COMPONENT(mission_source);

namespace robodds::mission_source {
namespace {

using robodds::testing::NodeHarness;

const char* kScenario = R"(name: mission_node
step_s: 0.01
duration_s: 0.05
seed: 1
robots:
  - {id: 1}
  - {id: 2}
components:
  - {name: mission, type: mission_source, params: {waypoints: [[1, 2], [3, 4]]}}
)";

void add_mission(NodeHarness& h) {
  robodds::component_registration::register_mission_source(h.registry());
}

TEST(MissionNode, PublishesEachRobotsMissionOnceAsFinal) {
  NodeHarness h(kScenario);
  add_mission(h);
  const auto& missions = h.record<idl::WaypointMission>("mission/waypoints");
  h.run({"mission"});
  ASSERT_EQ(missions.size(), 2u) << "once per robot, not once per step";
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(missions[i].robot_id(), i + 1);
    EXPECT_EQ(missions[i].header().step(), 0u);
    EXPECT_EQ(missions[i].header().next_step(), kNeverAgain);
    ASSERT_EQ(missions[i].waypoints().size(), 2u);
    EXPECT_DOUBLE_EQ(missions[i].waypoints()[1].x(), 3.0);
    EXPECT_DOUBLE_EQ(missions[i].waypoints()[1].y(), 4.0);
  }
}

TEST(MissionNode, AReaderThatJoinsAfterTheRunStillGetsTheMission) {
  NodeHarness h(kScenario);
  add_mission(h);
  h.run({"mission"});
  std::vector<std::uint32_t> late;
  const TopicInfo& info = topic_info("mission/waypoints");
  auto reader = h.bus().reader(info.name, info.type_name, qos_profile_for(info, TimeMode::kLockstep, true),
                               [&late](const void* p, const SampleMeta&) { late.push_back(static_cast<const idl::WaypointMission*>(p)->robot_id()); },
                               [](const std::string&) {});
  EXPECT_EQ(late, (std::vector<std::uint32_t>{1, 2})) << "the mission topic is transient local";
}

TEST(MissionNode, AnEmptyMissionIsAConfigError) {
  NodeHarness h(R"(name: mission_node
step_s: 0.01
duration_s: 0.05
seed: 1
robots:
  - {id: 1}
components:
  - {name: mission, type: mission_source, params: {waypoints: []}}
)");
  add_mission(h);
  EXPECT_THROW(h.run({"mission"}), ConfigError);
}

}  // namespace
}  // namespace robodds::mission_source
