#include "tools/robodds/compose.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "runtime/base/error.hpp"
#include "tests/support/temp_file.hpp"

namespace robodds {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

Scenario scenario_from(const std::string& text) {
  return load_scenario(test_support::write_test_file("compose_scenario.yaml", text));
}

const char* kTwoGroups = R"(name: demo
step_s: 0.01
duration_s: 1.0
seed: 3
robots:
  - {id: 1}
components:
  - {name: plant, type: plant}
  - {name: position_sensor, type: position_sensor}
  - {name: commander, type: open_loop_commander}
  - {name: odometry, type: odometry_sensor}
groups:
  sim: [plant]
  sensing: [position_sensor, odometry]
)";

ComposeOptions options_for(ComposeDiscovery discovery, ComposeNetwork network) {
  ComposeOptions o;
  o.discovery = discovery;
  o.network = network;
  o.scenario_path = "sim/scenarios/demo.yaml";
  o.component_types = {"plant", "position_sensor", "odometry_sensor", "open_loop_commander"};
  return o;
}

std::string generate(ComposeDiscovery discovery = ComposeDiscovery::kMulticast, ComposeNetwork network = ComposeNetwork::kBridge) {
  return generate_compose(scenario_from(kTwoGroups), options_for(discovery, network));
}

/// The text of one service block: from "  NAME:" to the next top-level service or section.
std::string service_block(const std::string& yaml, const std::string& name) {
  const std::size_t start = yaml.find("\n  " + name + ":\n");
  if (start == std::string::npos) {
    return "";
  }
  std::size_t end = start + 1;
  while (true) {
    end = yaml.find('\n', end + 1);
    if (end == std::string::npos || end + 3 >= yaml.size() || yaml.compare(end + 1, 4, "    ") != 0) {
      break;
    }
  }
  return yaml.substr(start, end == std::string::npos ? std::string::npos : end - start + 1);
}

std::string config_error(const Scenario& scenario, const ComposeOptions& options) {
  try {
    generate_compose(scenario, options);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Compose, OneServicePerGroupPlusCoordinatorInScenarioOrder) {
  const std::string yaml = generate();
  const std::size_t coordinator = yaml.find("\n  coordinator:\n");
  const std::size_t sim = yaml.find("\n  sim:\n");
  const std::size_t sensing = yaml.find("\n  sensing:\n");
  const std::size_t commander = yaml.find("\n  commander:\n");  // ungrouped: a group of its own
  ASSERT_NE(coordinator, std::string::npos);
  ASSERT_NE(sim, std::string::npos);
  ASSERT_NE(sensing, std::string::npos);
  ASSERT_NE(commander, std::string::npos);
  EXPECT_LT(coordinator, sim);
  EXPECT_LT(sim, sensing);
  EXPECT_LT(sensing, commander);
  EXPECT_THAT(yaml, Not(HasSubstr("\n  discovery:\n")));
}

TEST(Compose, HostCommandsMatchTheProcessRunner) {
  const std::string yaml = generate();
  EXPECT_THAT(service_block(yaml, "sensing"),
              HasSubstr("    command: [--scenario, /opt/robodds/sim/scenarios/demo.yaml, --group, sensing, --run-id, "
                        "\"${ROBODDS_RUN_ID:-1}\", --out, /opt/robodds/out/demo]\n"));
  EXPECT_THAT(service_block(yaml, "coordinator"),
              HasSubstr("    command: [--scenario, /opt/robodds/sim/scenarios/demo.yaml, --coordinate, --run-id, \"${ROBODDS_RUN_ID:-1}\"]\n"));
  EXPECT_THAT(yaml, HasSubstr("      ROBODDS_DOMAIN_ID: \"${ROBODDS_DOMAIN_ID:-0}\"\n"));
}

TEST(Compose, SharedImageBuiltFromTheRepositoryByTheFirstServiceOnly) {
  const std::string yaml = generate();
  EXPECT_THAT(service_block(yaml, "coordinator"),
              HasSubstr("    image: \"${ROBODDS_IMAGE:-robodds:latest}\"\n    build:  # the one image of every service\n"
                        "      context: ../..\n      dockerfile: deploy/docker/Dockerfile\n"));
  EXPECT_THAT(service_block(yaml, "sim"), HasSubstr("    image: \"${ROBODDS_IMAGE:-robodds:latest}\"\n"));
  EXPECT_THAT(service_block(yaml, "sim"), Not(HasSubstr("build:")));
  EXPECT_EQ(yaml.find("    build:"), yaml.rfind("    build:"));
  const std::string server = generate(ComposeDiscovery::kServer);
  EXPECT_THAT(service_block(server, "discovery"), HasSubstr("    build:"));
  EXPECT_EQ(server.find("    build:"), server.rfind("    build:"));
}

TEST(Compose, HeaderExtractsResultsFromTheScenarioFolderWhateverTheProject) {
  EXPECT_THAT(generate(), HasSubstr(" -C /opt/robodds/out -cf - demo | tar -xf - -C out/\n"));
}

TEST(Compose, MountsQosAndScenarioReadOnlyAndNoParameterFile) {
  const std::string sensing = service_block(generate(), "sensing");
  EXPECT_THAT(sensing, HasSubstr("      - \"../../deploy/qos:/opt/robodds/deploy/qos:ro\"\n"));
  EXPECT_THAT(sensing, HasSubstr("      - \"../../sim/scenarios/demo.yaml:/opt/robodds/sim/scenarios/demo.yaml:ro\"\n"));
  // Parameter defaults are compiled into the components; the scenario carries the overrides.
  EXPECT_THAT(sensing, Not(HasSubstr("params.yaml")));
  EXPECT_THAT(sensing, HasSubstr("      - \"results:/opt/robodds/out\"\n"));
}

TEST(Compose, BridgeMulticastUsesUdpOnlyOnAUserDefinedNetwork) {
  const std::string yaml = generate();
  EXPECT_THAT(service_block(yaml, "sim"), HasSubstr("      ROBODDS_PARTICIPANT_PROFILE: robodds.participant.udp_only\n"));
  EXPECT_THAT(service_block(yaml, "sim"), HasSubstr("      ROBODDS_QOS_FILE: /opt/robodds/deploy/qos/robodds_qos.xml\n"));
  EXPECT_THAT(service_block(yaml, "sim"), HasSubstr("    networks:\n      - robodds\n"));
  EXPECT_THAT(yaml, HasSubstr("\nnetworks:\n  robodds:\n    driver: bridge  # subnet chosen by docker"));
  EXPECT_THAT(yaml, Not(HasSubstr("ipam")));
  EXPECT_THAT(yaml, Not(HasSubstr("network_mode")));
}

TEST(Compose, DiscoveryServerOnTheBridgeIsFoundByNameWithoutAFixedSubnet) {
  const std::string yaml = generate(ComposeDiscovery::kServer);
  const std::string discovery = service_block(yaml, "discovery");
  EXPECT_THAT(discovery, HasSubstr("    entrypoint: [fastdds, discovery, \"-i\", \"0\", \"-l\", \"0.0.0.0\", \"-p\", \"11811\"]\n"));
  EXPECT_THAT(discovery, HasSubstr("    networks:\n      - robodds\n"));
  EXPECT_THAT(discovery, Not(HasSubstr("environment:")));
  // No address anywhere: docker picks the subnet, so two deployments can run on one engine.
  EXPECT_THAT(yaml, Not(HasSubstr("ipam")));
  EXPECT_THAT(yaml, Not(HasSubstr("ipv4_address")));
  EXPECT_THAT(yaml, Not(HasSubstr("172.")));
  const std::string sim = service_block(yaml, "sim");
  EXPECT_THAT(sim, HasSubstr("      ROBODDS_PARTICIPANT_PROFILE: robodds.participant.udp_only\n"));
  EXPECT_THAT(sim, HasSubstr("      ROBODDS_QOS_FILE: /opt/robodds/deploy/qos/robodds_qos.xml\n"));
  EXPECT_THAT(sim, HasSubstr("      ROS_DISCOVERY_SERVER: \"discovery:11811\""));
  EXPECT_THAT(sim, HasSubstr("    depends_on: [discovery]\n"));
  EXPECT_THAT(yaml, Not(HasSubstr("compose.xml")));
}

TEST(Compose, SecurityMountsEachServiceItsOwnIdentityReadOnly) {
  ComposeOptions options = options_for(ComposeDiscovery::kMulticast, ComposeNetwork::kBridge);
  options.security_dir = "/srv/sec";
  const std::string yaml = generate_compose(scenario_from(kTwoGroups), options);
  const std::string sim = service_block(yaml, "sim");
  EXPECT_THAT(sim, HasSubstr("      - \"/srv/sec/sim:/opt/robodds/security/sim:ro\"\n"));
  EXPECT_THAT(sim, HasSubstr(", --security, /opt/robodds/security"));
  EXPECT_THAT(sim, Not(HasSubstr("/srv/sec/sensing")));
  EXPECT_THAT(sim, Not(HasSubstr("/srv/sec/coordinator")));
  const std::string coordinator = service_block(yaml, "coordinator");
  EXPECT_THAT(coordinator, HasSubstr("      - \"/srv/sec/coordinator:/opt/robodds/security/coordinator:ro\"\n"));
  EXPECT_THAT(coordinator, HasSubstr(", --security, /opt/robodds/security"));
  EXPECT_THAT(service_block(yaml, "sensing"), HasSubstr("/srv/sec/sensing:/opt/robodds/security/sensing:ro"));
  // Nothing else of the folder (the CA, other identities) is mounted anywhere.
  EXPECT_THAT(yaml, Not(HasSubstr("/srv/sec:")));
  EXPECT_THAT(yaml, Not(HasSubstr("/srv/sec/ca")));
  EXPECT_THAT(generate(), Not(HasSubstr("--security")));
}

TEST(Compose, SecurityWithTheDiscoveryServerIsRefused) {
  ComposeOptions options = options_for(ComposeDiscovery::kServer, ComposeNetwork::kBridge);
  options.security_dir = "/srv/sec";
  EXPECT_THAT(config_error(scenario_from(kTwoGroups), options), HasSubstr("--security goes with --discovery multicast"));
}

TEST(Compose, HostNetworkSharesIpcAndUsesTheDefaultProfile) {
  const std::string yaml = generate(ComposeDiscovery::kMulticast, ComposeNetwork::kHost);
  const std::string sim = service_block(yaml, "sim");
  EXPECT_THAT(sim, HasSubstr("    network_mode: host\n    ipc: host  # share /dev/shm"));
  EXPECT_THAT(sim, HasSubstr("      ROBODDS_PARTICIPANT_PROFILE: robodds.participant\n"));
  EXPECT_THAT(yaml, Not(HasSubstr("\nnetworks:")));
}

TEST(Compose, HostNetworkDiscoveryServerUsesTheShippedLoopbackClientProfile) {
  const std::string yaml = generate(ComposeDiscovery::kServer, ComposeNetwork::kHost);
  EXPECT_THAT(service_block(yaml, "discovery"), HasSubstr("\"-l\", \"127.0.0.1\""));
  EXPECT_THAT(service_block(yaml, "sim"), HasSubstr("      ROBODDS_QOS_FILE: /opt/robodds/deploy/qos/discovery_client.xml\n"));
  EXPECT_THAT(yaml, Not(HasSubstr("compose.xml")));
}

TEST(Compose, Deterministic) { EXPECT_EQ(generate(ComposeDiscovery::kServer), generate(ComposeDiscovery::kServer)); }

TEST(Compose, RepoDirIsUsedForBuildContextAndMounts) {
  ComposeOptions options = options_for(ComposeDiscovery::kMulticast, ComposeNetwork::kBridge);
  options.repo_dir = "/srv/robodds";
  const std::string yaml = generate_compose(scenario_from(kTwoGroups), options);
  EXPECT_THAT(yaml, HasSubstr("      context: /srv/robodds\n"));
  EXPECT_THAT(yaml, HasSubstr("\"/srv/robodds/deploy/qos:/opt/robodds/deploy/qos:ro\""));
  EXPECT_THAT(yaml, Not(HasSubstr("../..")));
}

TEST(Compose, UnknownComponentTypeNamesComponentAndType) {
  std::string text = kTwoGroups;
  text.replace(text.find("type: plant}"), 12, "type: plantt}");
  const std::string error = config_error(scenario_from(text), options_for(ComposeDiscovery::kMulticast, ComposeNetwork::kBridge));
  EXPECT_THAT(error, HasSubstr("compose_scenario.yaml: components.plant: unknown component type 'plantt'; did you mean 'plant'? (known: "));
}

TEST(Compose, GroupNamedLikeAGeneratedServiceIsRejected) {
  std::string text = kTwoGroups;
  text.replace(text.find("  sim: [plant]"), 14, "  coordinator: [plant]");
  const std::string error = config_error(scenario_from(text), options_for(ComposeDiscovery::kMulticast, ComposeNetwork::kBridge));
  EXPECT_THAT(error, HasSubstr("groups.coordinator: group name 'coordinator' is reserved"));
}

TEST(Compose, GroupNameThatIsNoServiceNameIsRejected) {
  std::string text = kTwoGroups;
  text.replace(text.find("  sim: [plant]"), 14, "  \"s i m\": [plant]");
  const std::string error = config_error(scenario_from(text), options_for(ComposeDiscovery::kMulticast, ComposeNetwork::kBridge));
  EXPECT_THAT(error, HasSubstr("groups.s i m: group name 's i m' is not a valid compose service name"));
}

TEST(Compose, ScenarioNameThatIsNoDirectoryNameIsRejected) {
  std::string text = kTwoGroups;
  text.replace(text.find("name: demo"), 10, "name: \"de$mo\"");
  const std::string error = config_error(scenario_from(text), options_for(ComposeDiscovery::kMulticast, ComposeNetwork::kBridge));
  EXPECT_THAT(error, HasSubstr("compose_scenario.yaml: name: scenario name 'de$mo' is not usable"));
}

TEST(Compose, ScenarioGroupWithUnknownComponentFailsWhenLoading) {
  std::string text = kTwoGroups;
  text.replace(text.find("  sim: [plant]"), 14, "  sim: [plnt]");
  try {
    scenario_from(text);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr("groups.sim: unknown component 'plnt'"));
  }
}

}  // namespace
}  // namespace robodds
