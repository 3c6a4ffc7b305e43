#pragma once
// One `robodds` subcommand: registers its options on the application when made, runs once the
// command line names it. main() only parses and dispatches.

#include <CLI/CLI.hpp>

#include <atomic>
#include <memory>
#include <string>

#include "runtime/component/registry.hpp"

namespace robodds {

/// What every subcommand may use.
struct CommandEnv {
  const ComponentRegistry& registry;  // the component types robodds ships
  const std::atomic<bool>& stop;      // set by SIGINT / SIGTERM
  const std::string& log_level;       // the global --log (child processes get it too)
};

class Command {
 public:
  virtual ~Command() = default;
  /// True when the command line named this subcommand.
  virtual bool parsed() const = 0;
  /// Runs it; returns the exit code. Throws ConfigError (exit 2) or RunError (exit 1).
  virtual int run() = 0;
};

/// "on DDS domain D (`robodds topics --domain D` lists the topics seen there)": how every
/// "nothing seen" line of the topic tools (echo, hz, bw, info, record) ends.
inline std::string on_domain_text(int domain) {
  const std::string d = std::to_string(domain);
  return "on DDS domain " + d + " (`robodds topics --domain " + d + "` lists the topics seen there)";
}

std::unique_ptr<Command> add_run_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_host_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_coordinate_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_topics_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_echo_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_record_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_components_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_report_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_deploy_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_sweep_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_security_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_info_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_replay_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_bridge_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_hz_command(CLI::App& app, const CommandEnv& env);
std::unique_ptr<Command> add_bw_command(CLI::App& app, const CommandEnv& env);

}  // namespace robodds
