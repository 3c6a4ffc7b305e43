// `robodds run SCENARIO`: the whole scenario, co-located or one process per group, then the
// summary table and the plots.
#include <chrono>
#include <cstdio>
#include <unistd.h>

#include "runtime/launch/launch.hpp"
#include "runtime/base/log.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/summary_table.hpp"

namespace robodds {
namespace {

void show_progress(std::uint64_t step, std::uint64_t last) {
  static const bool on_terminal = isatty(STDERR_FILENO) != 0;  // a system call: ask once, not per tick
  if (!on_terminal) {
    return;
  }
  static auto last_print = std::chrono::steady_clock::now();
  const auto now = std::chrono::steady_clock::now();
  if (step != last && now - last_print < std::chrono::milliseconds(200)) {
    return;
  }
  last_print = now;
  std::fprintf(stderr, "\r  step %llu / %llu (%3.0f%%)%s", static_cast<unsigned long long>(step),
               static_cast<unsigned long long>(last), last > 0 ? 100.0 * static_cast<double>(step) / static_cast<double>(last) : 100.0,
               step == last ? "\n" : "");
}

class RunCommand : public Command {
 public:
  RunCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("run", "run a scenario (lockstep, co-located by default)");
    cmd_->add_option("scenario", scenario_file_, "scenario YAML file")->required();
    cmd_->add_option("--deploy", deploy_, "colocated (one process) or processes (one per group)")
        ->check(CLI::IsMember({"colocated", "processes"}));
    cmd_->add_option("--out", out_dir_, "output directory (default out/<scenario name>)");
    add_seed_option(cmd_, seed_, "override the scenario seed");
    cmd_->add_option("--set", sets_, "component.parameter=value over the scenario's (repeatable), e.g. controller.epsilon_m=0.01");
    cmd_->add_flag("--realtime", realtime_, "wall-clock timers instead of lockstep");
    add_duration_option(cmd_, duration_s_, "override the scenario duration (s)");
    add_max_missed_steps_option(cmd_, max_missed_steps_);
    add_rt_priority_option(cmd_, rt_priority_);
    add_dds_options(cmd_, dds_);
    add_lockstep_options(cmd_, lockstep_);
    cmd_->add_flag("--no-plots", no_plots_, "do not draw the PNG plots at the end");
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    // The runner first (before any participant or child exists; a refusal starts nothing), then
    // every child host applies it itself (a host starts at the runner's policy, a helper such as
    // the plots' python3 on SCHED_OTHER: ProcessGroup::spawn).
    apply_rt_priority_option(rt_priority_, "run", true);
    Scenario scenario = load_scenario(scenario_file_);
    apply_run_overrides(scenario, duration_s_, seed_);
    apply_param_overrides(scenario, parse_param_assignments(sets_), "--set");
    LaunchOptions launch;
    launch.scenario_file = scenario_file_;
    launch.sets = sets_;
    launch.deploy = deploy_ == "processes" ? Deploy::kProcesses : Deploy::kColocated;
    launch.realtime = realtime_;
    launch.out_dir = out_dir_.empty() ? "out/" + scenario.name : out_dir_;
    launch.lockstep = lockstep_;
    launch.log_level = env_.log_level;
    launch.max_missed_steps = max_missed_steps_;
    launch.rt_priority = rt_priority_;
    launch.progress = show_progress;
    launch.stop = &env_.stop;
    launch.dds = resolve_dds(dds_, "robodds-run");  // a bad $ROBODDS_DOMAIN_ID creates no --out
    make_output_dir(launch.out_dir);
    std::fflush(stdout);
    std::printf("robodds run %s: %s, %s, %llu steps of %g s, seed %llu\n", scenario.name.c_str(), deploy_.c_str(),
                realtime_ ? "real time" : "lockstep", static_cast<unsigned long long>(scenario.last_step() + 1),
                scenario.step_s, static_cast<unsigned long long>(scenario.seed));
    const RunStats stats = launch_run(env_.registry, scenario, launch);
    std::printf("done: %llu ticks in %.3f s (%.0f ticks/s)\n", static_cast<unsigned long long>(stats.steps), stats.wall_s,
                stats.wall_s > 0 ? static_cast<double>(stats.steps) / stats.wall_s : 0.0);
    std::fputs(summary_table(launch.out_dir).c_str(), stdout);
    if (!no_plots_ && draw_plots(launch.out_dir) != 0) {
      log::warn("run", "plots were not drawn (python3 with matplotlib missing?); the CSVs and summary.json are complete");
    }
    std::printf("results: %s\n", launch.out_dir.c_str());
    return 0;
  }

 private:
  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  std::string scenario_file_;
  std::string deploy_ = "colocated";
  std::string out_dir_;
  std::optional<std::uint64_t> seed_;
  std::vector<std::string> sets_;
  bool realtime_ = false;
  std::optional<double> duration_s_;
  std::optional<std::uint64_t> max_missed_steps_;
  std::optional<int> rt_priority_;
  bool no_plots_ = false;
  DdsArgs dds_;
  LockstepArgs lockstep_;
};

}  // namespace

std::unique_ptr<Command> add_run_command(CLI::App& app, const CommandEnv& env) { return std::make_unique<RunCommand>(app, env); }

}  // namespace robodds
