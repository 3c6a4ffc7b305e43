// The mission source node on the in-memory bus: publishes each robot's way-points once, final
// (next_step = never) on the transient-local mission topic.
#include "sim/mission_source/node/mission_source_node.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/io/io.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_test_scenario.hpp"

ROBODDS_DECLARE_COMPONENT(mission_source);

namespace robodds::mission_source {
namespace {

using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_mission_source>;

const std::string kScenario = ScenarioText("mission_node", 0.01, 0.05)
                                  .robots({1, 2})
                                  .component("{name: mission, type: mission_source, params: {waypoints: [[1, 2], [3, 4]]}}");

TEST(MissionNode, PublishesEachRobotsMissionOnceAsFinal) {
  Harness h(kScenario);
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
  Harness h(kScenario);
  h.run({"mission"});
  std::vector<std::uint32_t> late;
  const TopicInfo& info = topic_info("mission/waypoints");
  auto reader = h.bus().reader(info.name, info.type_name, qos_profile_for(info, TimeMode::kLockstep, true),
                               [&late](const void* p, const SampleMeta&) { late.push_back(static_cast<const idl::WaypointMission*>(p)->robot_id()); },
                               [](const std::string&) {});
  EXPECT_EQ(late, (std::vector<std::uint32_t>{1, 2})) << "the mission topic is transient local";
}

TEST(MissionNode, AnEmptyMissionIsAConfigError) {
  Harness h(ScenarioText("mission_node", 0.01, 0.05)
                .robots({1})
                .component("{name: mission, type: mission_source, params: {waypoints: []}}"));
  EXPECT_THROW(h.run({"mission"}), ConfigError);
}

}  // namespace
}  // namespace robodds::mission_source
