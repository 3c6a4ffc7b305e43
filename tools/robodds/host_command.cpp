// `robodds host`: some of a scenario's components (and/or the lockstep coordinator) in this
// process; the options are HostArgs (runtime/launch/host_args.hpp), which the runner renders.
#include "runtime/launch/launch.hpp"
#include "runtime/base/log.hpp"
#include "tools/cli/cli_main.hpp"
#include "tools/robodds/command.hpp"

namespace robodds {
namespace {

class HostCommand : public Command {
 public:
  HostCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("host", "run some of a scenario's components (or one component without a scenario) in this process");
    add_host_options(cmd_, args_);  // run_host() says which combinations are wrong
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    if (!args_.log_level.empty()) {
      log::set_level(log::parse_level(args_.log_level));
    }
    // SIGUSR1 (with a step: the runner of a real-time run across processes) stops it cleanly.
    return run_host(env_.registry, args_, &env_.stop, &cli::stop_flags().stop_at_step);
  }

 private:
  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  HostArgs args_;
};

}  // namespace

std::unique_ptr<Command> add_host_command(CLI::App& app, const CommandEnv& env) { return std::make_unique<HostCommand>(app, env); }

}  // namespace robodds
