#include "tools/component/component_main.hpp"

#include <CLI/CLI.hpp>

#include <string>

#include "common/param_doc.hpp"
#include "runtime/dds/process_exit.hpp"
#include "runtime/launch/host_args.hpp"
#include "runtime/launch/launch.hpp"
#include "runtime/base/log.hpp"
#include "tools/cli/cli_main.hpp"
#include "tools/component/executable_name.hpp"

namespace robodds {

int component_main(int argc, char** argv, const char* type, void (*register_type)(ComponentRegistry&)) {
  const std::atomic<bool>& stop = cli::install_stop_handlers();
  ComponentRegistry registry;
  register_type(registry);
  const ComponentType& component = registry.get(type);
  const std::string program = component_executable_name(component.name);

  CLI::App app{program + ": " + component.description + "\n(one component without a scenario file; in lockstep it "
                   "joins a run whose coordinator waits for its --member, by default its --name: `robodds coordinate "
                   "--members NAME,... --duration S` steps component executables; --realtime needs no coordinator)",
               program};
  HostArgs args;
  args.type = component.name;
  add_component_options(&app, args);
  app.footer("Parameters (--params FILE overrides them; defaults file: " + component.defaults_file + "):\n" +
             params::describe_params(component.params()));
  const int code = cli::parse_and_run(app, argc, argv, [&] {
    log::set_level(log::parse_level(!args.log_level.empty() ? args.log_level : cli::log_level_from_environment()));
    return run_host(registry, args, &stop, &cli::stop_flags().stop_at_step);  // SIGUSR1: end cleanly (real time), as robodds host
  });
  return exit_now_if_dds_is_closed(code);  // skips Fast DDS's 100 ms sleep at exit
}

}  // namespace robodds
