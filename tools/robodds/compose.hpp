#pragma once
// `robodds deploy compose`: a docker-compose file generated from a scenario's deployment
// groups, so the shipped files in deploy/compose/ cannot drift from the scenarios.
//
// Pure: no file system, no environment. The caller resolves paths and the component types'
// parameter files; the output depends only on the arguments (deterministic ordering).

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "runtime/config/scenario.hpp"

namespace robodds {

enum class ComposeDiscovery { kMulticast, kServer };
enum class ComposeNetwork { kBridge, kHost };

struct ComposeOptions {
  ComposeDiscovery discovery = ComposeDiscovery::kMulticast;
  ComposeNetwork network = ComposeNetwork::kBridge;
  /// The scenario file relative to the repository root, e.g. sim/scenarios/plant_smoke.yaml.
  std::string scenario_path;
  /// The repository root as seen from the compose file's directory (build context and the
  /// host side of every bind mount), e.g. "../.." for a file in deploy/compose/.
  std::string repo_dir = "../..";
  /// DDS Security (`--security DIR`): DIR as the compose file names it (host side of the mounts),
  /// empty = none. Each robodds service mounts its own identity DIR/<identity>/ read-only, at
  /// kSecurityDir/<identity> (the identity is its group, `coordinator` for the coordinator), and
  /// runs with --security kSecurityDir. Not with the Discovery Server (it would need an identity).
  std::string security_dir;
  /// --rt-priority N of every robodds service (the coordinator and the group hosts), which then
  /// get the capabilities and limits it needs (cap_add SYS_NICE and IPC_LOCK, ulimits rtprio 99 and
  /// memlock unlimited); nullopt: none of these.
  std::optional<int> rt_priority;
  /// The registered component types; a scenario component of another type is an error. (No
  /// parameter file is mounted: defaults are compiled in, scenario overrides are in the scenario.)
  std::vector<std::string> component_types;
};

/// Fixed names and addresses of the generated deployments (also used by the tests and docs).
struct ComposeConstants {
  /// The image every service runs: $ROBODDS_IMAGE when compose reads the file, else robodds:latest.
  static constexpr const char* kImage = "${ROBODDS_IMAGE:-robodds:latest}";
  static constexpr const char* kDockerfile = "deploy/docker/Dockerfile";
  static constexpr const char* kShareDir = "/opt/robodds";  // ROBODDS_SHARE_DIR in the image
  static constexpr const char* kNetwork = "robodds";
  static constexpr int kDiscoveryPort = 11811;
  static constexpr const char* kSecurityDir = "/opt/robodds/security";  // --security in the containers
  static constexpr const char* kCoordinatorService = "coordinator";
  static constexpr const char* kDiscoveryService = "discovery";
};

/// The compose file's YAML text. Throws ConfigError naming the scenario file and the offending
/// group or component (unknown component type, group name unusable as a service name).
std::string generate_compose(const Scenario& scenario, const ComposeOptions& options);

/// "multicast"/"server" and "bridge"/"host", as on the command line.
const char* to_string(ComposeDiscovery discovery);
const char* to_string(ComposeNetwork network);

}  // namespace robodds
