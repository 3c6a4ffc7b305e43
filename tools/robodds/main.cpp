// robodds: run scenarios, host components, inspect topics. This file only parses the command
// line and dispatches to one Command per subcommand (tools/robodds/*_command.cpp).
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>

#include "runtime/error.hpp"
#include "runtime/log.hpp"
#include "runtime/registry.hpp"
#include "tools/robodds/command.hpp"

namespace {

std::atomic<bool> g_stop{false};

void on_signal(int) { g_stop = true; }

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace robodds;
  install_signal_handlers();
  CLI::App app{"robodds: deterministic DDS component system (run scenarios, host components, inspect topics)"};
  app.require_subcommand(1);
  const char* env_log = std::getenv("ROBODDS_LOG");
  std::string log_level = env_log != nullptr && *env_log != '\0' ? env_log : "info";
  app.add_option("--log", log_level, "log level: debug, info, warn, error");

  ComponentRegistry registry;
  register_builtin_components(registry);
  const CommandEnv env{registry, g_stop, log_level};
  std::vector<std::unique_ptr<Command>> commands;
  for (auto add : {add_run_command, add_host_command, add_topics_command, add_echo_command, add_components_command,
                   add_report_command, add_deploy_command}) {
    commands.push_back(add(app, env));
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help and friends: CLI11 prints and exits 0
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Bad command line = bad input: one line and exit code 2, like every other ConfigError.
    std::fprintf(stderr, "robodds: error: %s (see robodds %s--help)\n", e.what(),
                 app.get_subcommands().empty() ? "" : (app.get_subcommands().front()->get_name() + " ").c_str());
    return 2;
  }

  try {
    log::set_level(log::parse_level(log_level));
    for (const auto& command : commands) {
      if (command->parsed()) {
        return command->run();
      }
    }
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "robodds: error: %s\n", e.what());
    return 2;
  } catch (const RunError& e) {
    std::fprintf(stderr, "robodds: error: %s\n", e.what());
    return g_stop ? 130 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "robodds: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
