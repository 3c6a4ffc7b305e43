// `robodds run SCENARIO`: the whole scenario, co-located or one process per group, then the
// summary table and the plots.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "runtime/component/param_keys.hpp"
#include "runtime/base/error.hpp"
#include "runtime/launch/added_components.hpp"
#include "runtime/launch/launch.hpp"
#include "runtime/mcap/compression.hpp"
#include "runtime/base/log.hpp"
#include "tools/cli/cli_main.hpp"
#include "tools/cli/one_of.hpp"
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

/// The recorder `--record` adds: its instance name (and type).
constexpr const char* kRecorderName = "run_recorder";

/// The group the recorder joins: the evaluator's (it records the run already; its host waits
/// for every published topic at the end anyway), else the scenario's last group.
std::string recording_group(const Scenario& scenario) {
  for (const GroupSpec& group : scenario.groups) {
    for (const std::string& name : group.components) {
      if (scenario.component(name).type == "evaluator") {
        return group.name;
      }
    }
  }
  if (scenario.groups.empty()) {
    throw ConfigError("--record: " + scenario.file + " has no group to add the recorder to");
  }
  return scenario.groups.back().name;
}

/// `path` made absolute (the child hosts of --deploy processes write it), after checking it can
/// be written: one line before the run starts (exit 2), not a failed run.
std::string checked_record_path(const std::string& path) {
  const std::string absolute = std::filesystem::absolute(path).lexically_normal().string();
  const int fd = ::open(absolute.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw ConfigError("--record " + path + ": cannot write it (" + std::strerror(errno) + ")");
  }
  ::close(fd);
  return absolute;
}

class RunCommand : public Command {
 public:
  RunCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("run", "run a scenario (lockstep, co-located by default)");
    cmd_->add_option("scenario", scenario_file_, "scenario YAML file")->required();
    cmd_->add_option("--deploy", deploy_, "colocated (one process) or processes (one per group)")
        ->check(cli::one_of({"colocated", "processes"}));
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
    cmd_->add_option("--record", record_,
                     "record the topics the scenario's components publish into this MCAP file, from inside the run "
                     "(lockstep: sim times, the same file co-located and across processes; docs/record-replay.md)");
    cmd_->add_option("--record-compression", record_compression_, "with --record: chunk compression zstd, lz4 or none");
    cmd_->add_option("--record-topics", record_topics_, "with --record: only these topics (comma separated; default all published)")
        ->delimiter(',');
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    // The runner first (before any participant or child exists; a refusal starts nothing), then
    // every child host applies it itself (a host starts at the runner's policy, a helper such as
    // the plots' python3 on SCHED_OTHER: ProcessGroup::spawn).
    apply_rt_priority_option(rt_priority_, "run", true);
    Scenario scenario = load_scenario(scenario_file_);
    const std::vector<std::string> added = record_components(scenario);
    add_components(scenario, added);
    apply_run_overrides(scenario, duration_s_, seed_);
    check_param_keys(scenario, env_.registry, sets_, "--set");
    apply_param_overrides(scenario, parse_param_assignments(sets_), "--set");
    LaunchOptions launch;
    launch.scenario_file = scenario_file_;
    launch.sets = sets_;
    launch.added_components = added;
    launch.deploy = deploy_ == "processes" ? Deploy::kProcesses : Deploy::kColocated;
    launch.realtime = realtime_;
    launch.out_dir = out_dir_.empty() ? "out/" + scenario.name : out_dir_;
    launch.lockstep = lockstep_;
    launch.log_level = env_.log_level;
    launch.max_missed_steps = max_missed_steps_;
    launch.rt_priority = rt_priority_;
    launch.progress = show_progress;
    // Real time: the first SIGINT/SIGTERM stops the run cleanly at its next step (summary
    // "completed", "stopped_by": "signal"), a second aborts; lockstep: the first aborts (an
    // interrupted deterministic run is "failed").
    const cli::StopFlags& stop = cli::stop_flags();
    launch.stop = realtime_ ? &stop.second_signal : &env_.stop;
    launch.graceful_stop = realtime_ ? &stop.first_signal : nullptr;
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
  /// With --record: the recorder to add (and its parameters appended to the --set list, which
  /// every child host applies too); nothing otherwise.
  std::vector<std::string> record_components(const Scenario& scenario) {
    if (record_.empty()) {
      if (!record_topics_.empty() || record_compression_ != "zstd") {
        throw ConfigError("--record-topics and --record-compression go with --record FILE.mcap");
      }
      return {};
    }
    mcap::parse_compression(record_compression_, "--record-compression");
    const std::string recorder = kRecorderName;
    sets_.push_back(recorder + ".file=" + checked_record_path(record_));
    sets_.push_back(recorder + ".compression=" + record_compression_);
    if (!record_topics_.empty()) {
      std::string list;
      for (const std::string& topic : record_topics_) {
        list += (list.empty() ? "" : ", ") + topic;
      }
      sets_.push_back(recorder + ".topics=[" + list + "]");
    }
    return {added_component_spec(recording_group(scenario), recorder, kRecorderName)};
  }

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
  std::string record_;
  std::string record_compression_ = "zstd";
  std::vector<std::string> record_topics_;
  DdsArgs dds_;
  LockstepArgs lockstep_;
};

}  // namespace

std::unique_ptr<Command> add_run_command(CLI::App& app, const CommandEnv& env) { return std::make_unique<RunCommand>(app, env); }

}  // namespace robodds
