// The DDS Security policy of a scenario (tools/robodds/security_policy.hpp): each group may
// publish exactly what its components publish, read exactly what they read, plus its lockstep
// protocol; the documents carry those lists and deny the rest.
#include "tools/robodds/security_policy.hpp"

#include <gtest/gtest.h>

#include "runtime/base/error.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/topics/topic_catalog.hpp"

namespace robodds {
namespace {

const SecurityIdentity& find(const std::vector<SecurityIdentity>& ids, const std::string& name) {
  for (const SecurityIdentity& id : ids) {
    if (id.name == name) {
      return id;
    }
  }
  throw std::runtime_error("no identity " + name);
}

std::vector<SecurityIdentity> plant_smoke_identities() {
  static ComponentRegistry registry = [] {
    ComponentRegistry r;
    register_builtin_components(r);
    return r;
  }();
  const Scenario scenario = load_scenario(std::string(ROBODDS_SOURCE_DIR) + "/sim/scenarios/plant_smoke.yaml");
  return security_identities(scenario, scenario_component_topics(registry, scenario, TimeMode::kLockstep));
}

using Topics = std::set<std::string>;

TEST(SecurityPolicy, EachGroupPublishesAndReadsExactlyWhatItsComponentsDo) {
  const auto ids = plant_smoke_identities();
  // control: the open-loop commander writes plant/cmd and reads nothing.
  EXPECT_EQ(find(ids, "control").publishes, (Topics{"plant/cmd", "run/alive", "run/health", "sim/step_done"}));
  EXPECT_EQ(find(ids, "control").subscribes, (Topics{"run/alive", "sim/clock"}));
  // sim: the plant reads the commands and writes the state.
  EXPECT_EQ(find(ids, "sim").publishes, (Topics{"plant/state", "run/alive", "run/health", "sim/step_done"}));
  EXPECT_EQ(find(ids, "sim").subscribes, (Topics{"plant/cmd", "run/alive", "sim/clock"}));
  // evaluation reads what its `topics` parameter names, and the other hosts' health reports.
  EXPECT_EQ(find(ids, "evaluation").subscribes,
            (Topics{"plant/cmd", "plant/state", "run/alive", "run/health", "sensor/position", "sim/clock"}));
  EXPECT_EQ(find(ids, "coordinator").publishes, (Topics{"sim/clock"}));
  EXPECT_EQ(find(ids, "coordinator").subscribes, (Topics{"sim/step_done"}));
  EXPECT_TRUE(find(ids, "tools").publishes.empty());
  EXPECT_EQ(find(ids, "tools").subscribes.size(), topic_catalog().size());
  // The co-located run is every group and the coordinator in one participant.
  EXPECT_EQ(find(ids, "colocated").publishes.count("plant/cmd"), 1u);
  EXPECT_EQ(find(ids, "colocated").publishes.count("sim/clock"), 1u);
}

TEST(SecurityPolicy, PermissionsListTheTopicsAndDenyTheRest) {
  const auto ids = plant_smoke_identities();
  const std::string xml = permissions_xml(find(ids, "sim"), "CN=sim@plant_smoke", "2026-01-01T00:00:00", "2027-01-01T00:00:00");
  EXPECT_NE(xml.find("<subject_name>CN=sim@plant_smoke</subject_name>"), std::string::npos);
  EXPECT_NE(xml.find("<publish>\n          <topics>\n            <topic>plant/state</topic>"), std::string::npos);
  EXPECT_NE(xml.find("<subscribe>\n          <topics>\n            <topic>plant/cmd</topic>"), std::string::npos);
  EXPECT_NE(xml.find("<default>DENY</default>"), std::string::npos);
  EXPECT_NE(xml.find("<not_after>2027-01-01T00:00:00</not_after>"), std::string::npos);
  // Only the publish section names plant/state: sim does not read its own output.
  EXPECT_EQ(xml.find("plant/state"), xml.rfind("plant/state"));
  // A tool that publishes nothing has no publish section at all.
  const std::string tools = permissions_xml(find(ids, "tools"), "CN=tools@x", "a", "b");
  EXPECT_EQ(tools.find("<publish>"), std::string::npos);
}

TEST(SecurityPolicy, GovernanceEncryptsPayloadsAndControlsEveryTopic) {
  const std::string xml = governance_xml();
  EXPECT_NE(xml.find("<allow_unauthenticated_participants>false</allow_unauthenticated_participants>"), std::string::npos);
  EXPECT_NE(xml.find("<enable_write_access_control>true</enable_write_access_control>"), std::string::npos);
  EXPECT_NE(xml.find("<data_protection_kind>ENCRYPT</data_protection_kind>"), std::string::npos);
  EXPECT_NE(xml.find("<enable_read_access_control>true</enable_read_access_control>"), std::string::npos);
  EXPECT_NE(xml.find("<enable_join_access_control>true</enable_join_access_control>"), std::string::npos);
}

TEST(SecurityPolicy, GovernanceEncryptsDiscoveryAndLiveliness) {
  const std::string xml = governance_xml();
  EXPECT_NE(xml.find("<discovery_protection_kind>ENCRYPT</discovery_protection_kind>"), std::string::npos);
  EXPECT_NE(xml.find("<liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>"), std::string::npos);
  EXPECT_NE(xml.find("<enable_discovery_protection>true</enable_discovery_protection>"), std::string::npos);
  EXPECT_NE(xml.find("<enable_liveliness_protection>true</enable_liveliness_protection>"), std::string::npos);
  // Off by choice (docs/security.md, threat model): submessage metadata (costly, not enforced by
  // Fast DDS 2.9.1 receivers) and whole RTPS messages.
  EXPECT_NE(xml.find("<metadata_protection_kind>NONE</metadata_protection_kind>"), std::string::npos);
  EXPECT_NE(xml.find("<rtps_protection_kind>NONE</rtps_protection_kind>"), std::string::npos);
}

TEST(SecurityPolicy, AGroupNamedLikeAToolIdentityIsRefused) {
  Scenario scenario;
  scenario.file = "s.yaml";
  scenario.groups.push_back(GroupSpec{"coordinator", {}});
  try {
    security_identities(scenario, {});
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("s.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("reserved"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace robodds
