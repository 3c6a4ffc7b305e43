// robodds: run scenarios, host components, inspect topics. This file only parses the command
// line and dispatches to one Command per subcommand (tools/robodds/*_command.cpp).
#include <CLI/CLI.hpp>

#include "runtime/dds/process_exit.hpp"
#include "runtime/base/log.hpp"
#include "runtime/component/registry.hpp"
#include "tools/cli/cli_main.hpp"
#include "tools/robodds/command.hpp"

int main(int argc, char** argv) {
  using namespace robodds;
  const std::atomic<bool>& stop = cli::install_stop_handlers();
  CLI::App app{"robodds: deterministic DDS component system (run scenarios, host components, inspect topics)", "robodds"};
  app.require_subcommand(1);
  std::string log_level = cli::log_level_from_environment();
  app.add_option("--log", log_level, "log level: debug, info, warn, error");

  ComponentRegistry registry;
  register_builtin_components(registry);
  const CommandEnv env{registry, stop, log_level};
  std::vector<std::unique_ptr<Command>> commands;
  for (auto add : {add_run_command, add_host_command, add_coordinate_command, add_topics_command, add_echo_command, add_record_command,
                   add_components_command, add_report_command, add_deploy_command, add_sweep_command, add_security_command,
                   add_info_command, add_replay_command, add_bridge_command,
                   add_hz_command, add_bw_command}) {
    commands.push_back(add(app, env));
  }
  const int code = cli::parse_and_run(app, argc, argv, [&] {
    log::set_level(log::parse_level(log_level));
    for (const auto& command : commands) {
      if (command->parsed()) {
        return command->run();
      }
    }
    return 0;
  });
  return exit_now_if_dds_is_closed(code);  // skips Fast DDS's 100 ms sleep at exit
}
