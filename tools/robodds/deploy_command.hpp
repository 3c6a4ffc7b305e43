#pragma once
// `robodds deploy compose SCENARIO [--discovery multicast|server] [--network bridge|host] [-o FILE]`:
// command-line wiring and path handling around the pure generator in compose.hpp.

#include <CLI/CLI.hpp>

#include <string>

namespace robodds {

class DeployCommand {
 public:
  /// Registers `deploy` and its `compose` subcommand on the application.
  explicit DeployCommand(CLI::App& app);

  bool parsed() const { return deploy_->parsed(); }

  /// Generates the compose file. repo_root is the source tree (share dir) that holds the
  /// scenario, the QoS files and the parameter files. Throws ConfigError on bad input.
  int run(const std::string& repo_root) const;

 private:
  CLI::App* deploy_ = nullptr;
  std::string scenario_file_;
  std::string discovery_ = "multicast";
  std::string network_ = "bridge";
  std::string output_;
};

}  // namespace robodds
