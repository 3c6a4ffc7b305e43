// `robodds coordinate`: a lockstep coordinator without a scenario file, for a robot made of
// component executables (robodds-<type>): it waits for every --members, ticks them every --step
// until --duration and exits 0, or names the member that failed, died or never came. It is
// `robodds host --coordinate` (the same coordinator, runtime/lockstep/) with the scenario made
// from these options (runtime/launch/coordinator_scenario.hpp).
#include "runtime/launch/coordinator_scenario.hpp"
#include "runtime/launch/launch.hpp"
#include "runtime/base/log.hpp"
#include "tools/robodds/command.hpp"

namespace robodds {
namespace {

class CoordinateCommand : public Command {
 public:
  CoordinateCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("coordinate",
                              "step component executables (robodds-<type>) in lockstep without a scenario file: wait for "
                              "every --members, tick every --step until --duration, exit 0 at the end");
    args_.coordinate = true;
    cmd_->add_option("--members", members_,
                     "members to wait for and step, comma separated: each executable's --member (default its --name, "
                     "default its type)");
    add_step_option(cmd_, args_.step_s, "simulation step (s, default 0.01); every member's --step must agree");
    add_duration_option(cmd_, args_.duration_s, "simulated time of the run (s, required): the final tick ends every member");
    cmd_->add_option("--run-id", args_.run_id, "run id of the members' --run-id (default 1, theirs too)");
    cmd_->add_option("--start-timeout", args_.lockstep.start_timeout_s,
                     "s, max wait for every member's first acknowledgement (the members still missing are named)");
    cmd_->add_option("--lockstep-window", args_.lockstep.lockstep_window,
                     "ticks outstanding at once (1 = strict; more pipelines the members, same results; at most 32; give "
                     "the members the same value, they check their writer history against it)")
        ->check(CLI::Range(1, 32));
    cmd_->add_option("--log", args_.log_level, "log level: debug, info, warn, error (default: the global --log)");
    add_dds_options(cmd_, args_.dds);
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    if (!args_.log_level.empty()) {
      log::set_level(log::parse_level(args_.log_level));
    }
    args_.members = split_members(members_);  // an empty name stays, for check_members() to name
    return run_host(env_.registry, args_, &env_.stop);
  }

 private:
  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  HostArgs args_;
  std::string members_;  // --members as given
};

}  // namespace

std::unique_ptr<Command> add_coordinate_command(CLI::App& app, const CommandEnv& env) {
  return std::make_unique<CoordinateCommand>(app, env);
}

}  // namespace robodds
