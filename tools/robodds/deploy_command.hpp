#pragma once
// `robodds deploy compose SCENARIO [--discovery multicast|server] [--network bridge|host]
// [--rt-priority N] [-o FILE]`:
// command-line wiring and path handling around the pure generator in compose.hpp.

#include <optional>
#include <string>

#include "tools/robodds/command.hpp"

namespace robodds {

class DeployCommand : public Command {
 public:
  /// Registers `deploy` and its `compose` subcommand on the application.
  DeployCommand(CLI::App& app, const CommandEnv& env);

  bool parsed() const override { return deploy_->parsed(); }

  /// Generates the compose file from the source tree (share dir) that holds the scenario, the
  /// QoS files and the parameter files. Throws ConfigError on bad input.
  int run() override;

 private:
  const CommandEnv& env_;
  CLI::App* deploy_ = nullptr;
  std::string scenario_file_;
  std::string discovery_ = "multicast";
  std::string network_ = "bridge";
  std::string output_;
  std::string security_dir_;  // empty: no DDS Security
  std::optional<int> rt_priority_;  // --rt-priority of every robodds service, with its capabilities
};

}  // namespace robodds
