#include "tools/robodds/deploy_command.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "runtime/dds/security_files.hpp"
#include "runtime/base/error.hpp"
#include "runtime/launch/launch.hpp"
#include "runtime/config/scenario.hpp"
#include "tools/cli/one_of.hpp"
#include "tools/robodds/compose.hpp"

namespace robodds {
namespace {

namespace fs = std::filesystem;

/// True when `path` is `root` or below it (both canonical).
bool is_inside(const fs::path& path, const fs::path& root) {
  const fs::path rel = path.lexically_relative(root);
  return !rel.empty() && *rel.begin() != "..";
}

/// How the compose file reaches the repository: relative when the file is inside it (the
/// shipped files stay valid in any checkout), absolute otherwise.
std::string repo_dir_seen_from(const fs::path& compose_dir, const fs::path& root) {
  if (!is_inside(compose_dir, root)) {
    return root.string();
  }
  const std::string rel = root.lexically_relative(compose_dir).generic_string();
  return rel.empty() ? "." : rel;
}

void require_in_repo(const fs::path& root, const std::string& repo_path, const std::string& what) {
  if (!fs::exists(root / repo_path)) {
    throw ConfigError(located((root / repo_path).string(), "", what + " not found (the compose file mounts it from the repository)"));
  }
}

}  // namespace

DeployCommand::DeployCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
  deploy_ = app.add_subcommand("deploy", "generate deployment files from a scenario");
  deploy_->require_subcommand(1);
  CLI::App* compose = deploy_->add_subcommand("compose", "docker-compose file: one service per group of the scenario + coordinator");
  compose->add_option("scenario", scenario_file_, "scenario YAML file (inside the repository)")->required();
  compose->add_option("--discovery", discovery_, "multicast (SIMPLE discovery) or server (a Fast DDS Discovery Server service)")
      ->check(cli::one_of({"multicast", "server"}));
  compose->add_option("--network", network_, "bridge (user-defined network, UDP only) or host (network_mode: host, ipc: host)")
      ->check(cli::one_of({"bridge", "host"}));
  compose->add_option("--security", security_dir_,
                      "DDS Security: directory made by `robodds security init`; each container mounts its own identity, read-only");
  add_rt_priority_option(compose, rt_priority_);
  compose->add_option("-o,--output", output_, "write here (default: stdout, with paths for a file in deploy/compose/)");
}

int DeployCommand::run() {
  const Scenario scenario = load_scenario(scenario_file_);
  const fs::path root = fs::canonical(share_dir());
  const fs::path scenario_abs = fs::canonical(scenario_file_);
  if (!is_inside(scenario_abs, root)) {
    throw ConfigError(located(scenario_file_, "", "is outside the repository " + root.string() +
                                                      " (the image and the mounts take scenarios from there, e.g. sim/scenarios/)"));
  }

  ComposeOptions options;
  options.discovery = discovery_ == "server" ? ComposeDiscovery::kServer : ComposeDiscovery::kMulticast;
  options.network = network_ == "host" ? ComposeNetwork::kHost : ComposeNetwork::kBridge;
  options.scenario_path = scenario_abs.lexically_relative(root).generic_string();
  if (!output_.empty()) {
    options.repo_dir = repo_dir_seen_from(fs::weakly_canonical(fs::absolute(output_)).parent_path(), root);
  }
  for (const ComponentType& type : env_.registry.types()) {
    options.component_types.push_back(type.name);
  }
  options.rt_priority = rt_priority_;
  if (!security_dir_.empty()) {  // absolute in the file: the folder is usually outside the repository
    options.security_dir = fs::weakly_canonical(fs::absolute(security_dir_)).generic_string();
  }

  const std::string text = generate_compose(scenario, options);  // validates groups and types first
  if (!security_dir_.empty()) {
    // Every identity the containers use, checked now (missing, expired, of another CA...), not at `up`.
    check_security_files(security_dir_, kCoordinatorIdentity);
    for (const GroupSpec& group : scenario.groups) {
      check_security_files(security_dir_, group.name);
    }
  }

  // Everything the file mounts must exist, or docker would mount an empty directory instead.
  require_in_repo(root, "deploy/qos/robodds_qos.xml", "QoS file");
  if (options.discovery == ComposeDiscovery::kServer) {
    if (options.network == ComposeNetwork::kHost) {
      require_in_repo(root, "deploy/qos/discovery_client.xml", "discovery client profile");
    }
  }

  if (output_.empty()) {
    std::fputs(text.c_str(), stdout);
    return 0;
  }
  std::ofstream out(output_, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) {
    throw ConfigError(located(output_, "", "cannot write the compose file"));
  }
  std::printf("wrote %s (%zu groups + coordinator%s)\n", output_.c_str(), scenario.groups.size(),
              options.discovery == ComposeDiscovery::kServer ? " + discovery server" : "");
  return 0;
}

std::unique_ptr<Command> add_deploy_command(CLI::App& app, const CommandEnv& env) {
  return std::make_unique<DeployCommand>(app, env);
}

}  // namespace robodds
