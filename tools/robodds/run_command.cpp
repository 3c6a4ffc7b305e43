// `robodds run SCENARIO`: the whole scenario, co-located or one process per group, then the
// plots and a short report (--verbose: every figure of summary.json, --quiet: the output path,
// --json: summary.json on stdout).
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include "runtime/component/param_keys.hpp"
#include "runtime/base/error.hpp"
#include "runtime/launch/added_components.hpp"
#include "runtime/launch/launch.hpp"
#include "runtime/mcap/compression.hpp"
#include "runtime/base/log.hpp"
#include "tools/cli/cli_main.hpp"
#include "runtime/base/log_count.hpp"
#include "tools/cli/one_of.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/module_headlines.hpp"
#include "tools/robodds/progress.hpp"
#include "tools/robodds/run_report.hpp"
#include "tools/robodds/summary_table.hpp"

namespace robodds {
namespace {

/// The progress line on stderr (progress.hpp), timed from its making (just before the run starts).
class RunProgress {
 public:
  RunProgress(double step_s, bool shown) : step_s_(step_s), shown_(shown), pacer_(isatty(STDERR_FILENO) != 0) {}

  void operator()(std::uint64_t step, std::uint64_t last) {
    if (!shown_) {
      return;
    }
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (pacer_.due(step, last, wall_s)) {
      std::fputs(progress_output("  " + run_progress_text(step, last, step_s_, wall_s), pacer_.terminal(), step >= last).c_str(),
                 stderr);
      *open_line_ = pacer_.terminal() && step < last;
    }
  }

  /// Ends a live line the run left unfinished (it failed, was stopped, or ended between two lines),
  /// so the report starts on a line of its own.
  void close() const {
    if (*open_line_) {
      std::fputs("\n", stderr);
      *open_line_ = false;
    }
  }

  /// Wall time since the start, s.
  double elapsed_s() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  double step_s_;
  bool shown_;
  ProgressPacer pacer_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::shared_ptr<bool> open_line_ = std::make_shared<bool>(false);  // shared with the copy launch_run() calls
};

/// How many files in `dir` (not below) end in `extension`.
std::size_t files_ending(const std::string& dir, const std::string& extension) {
  std::size_t n = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    n += entry.path().extension() == extension ? 1 : 0;
  }
  return n;
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
    CLI::Option* verbose = cmd_->add_flag("--verbose", verbose_, "end with every figure of summary.json (and the plots' paths)");
    CLI::Option* quiet = cmd_->add_flag("--quiet", quiet_, "print only errors and the output directory");
    CLI::Option* json = cmd_->add_flag("--json", json_, "print summary.json on stdout (and nothing else there)");
    verbose->excludes(quiet)->excludes(json);
    quiet->excludes(json);
    cmd_->add_option("--record", record_,
                     "record the topics the scenario's components publish into this MCAP file, from inside the run "
                     "(lockstep: sim times, the same file co-located and across processes; docs/record-replay.md)");
    cmd_->add_option("--record-compression", record_compression_, "with --record: chunk compression zstd, lz4 or none");
    cmd_->add_option("--record-topics", record_topics_, "with --record: only these topics (comma separated; default all published)")
        ->delimiter(',');
    cmd_->add_flag("--record-foxglove-scene", record_foxglove_scene_,
                   "with --record: also write foxglove/robot_poses, every robot's pose from plant/state as a "
                   "foxglove.PosesInFrame (JSON) at most every 50 ms of the samples' stamps, drawn by Foxglove's 3D panel");
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    // Line by line even when piped: the header and report keep their places among the log's
    // stderr lines (a pipe's full buffering would print the header after an error).
    std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
    if (quiet_ && log::level() < log::Level::kError) {
      log::set_level(log::Level::kError);
    }
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
    launch.log_level = quiet_ ? std::string("error") : env_.log_level;
    launch.max_missed_steps = max_missed_steps_;
    launch.rt_priority = rt_priority_;
    const RunProgress progress(scenario.step_s, !quiet_);
    launch.progress = progress;
    // Real time: the first SIGINT/SIGTERM stops the run cleanly at its next step (summary
    // "completed", "stopped_by": "signal"), a second aborts; lockstep: the first aborts (an
    // interrupted deterministic run is "failed").
    const cli::StopFlags& stop = cli::stop_flags();
    launch.stop = realtime_ ? &stop.second_signal : &env_.stop;
    launch.graceful_stop = realtime_ ? &stop.first_signal : nullptr;
    launch.dds = resolve_dds(dds_, "robodds-run");  // a bad $ROBODDS_DOMAIN_ID creates no --out
    make_output_dir(launch.out_dir);
    if (!quiet_) {
      std::fprintf(json_ ? stderr : stdout, "robodds run %s: %s, %s, %llu steps of %g s, seed %llu\n", scenario.name.c_str(),
                   deploy_.c_str(), realtime_ ? "real time" : "lockstep", static_cast<unsigned long long>(scenario.last_step() + 1),
                   scenario.step_s, static_cast<unsigned long long>(scenario.seed));
    }
    const std::uint64_t warnings_before = log::warnings_written();
    RunStats stats;
    try {
      stats = launch_run(env_.registry, scenario, launch);
    } catch (const RunError&) {
      // A failed run keeps its CSVs and summary.json: say where, then the error line (cli_main).
      progress.close();
      report(scenario, launch.out_dir, std::nullopt, progress.elapsed_s(), warnings_before, false);
      throw;
    }
    progress.close();  // a real-time run may end (or be stopped) between two progress lines
    const bool plots = !no_plots_ && plot(launch.out_dir);
    // A signal while drawing (python3 got it too): the run is complete, the plots are not; end
    // as a signal ends any command. Real time: the first signal was the graceful stop itself.
    if (realtime_ ? stop.second_signal.load() : env_.stop.load()) {
      throw RunError("stopped by a signal while drawing the plots; the run's CSVs and summary.json are complete (`robodds report " +
                     launch.out_dir + "` draws them)");
    }
    report(scenario, launch.out_dir, stats, stats.wall_s, warnings_before, plots);
    return 0;
  }

 private:
  /// Draws the plots; true if drawn. Their paths go to OUT/plots.log unless --verbose.
  bool plot(const std::string& out_dir) const {
    const std::string log_file = verbose_ ? "" : out_dir + "/plots.log";
    if (draw_plots(out_dir, 600.0, log_file) == 0) {
      return true;
    }
    log::warn("run", "plots were not drawn (python3 with matplotlib missing?" + (log_file.empty() ? "" : " see " + log_file) +
                         "); the CSVs and summary.json are complete");
    return false;
  }

  /// The end of the run on stdout: the short report, every figure (--verbose), the output
  /// directory (--quiet) or summary.json (--json).
  /// `stats`: the run's, none when it failed; `wall_s`: its wall time.
  void report(const Scenario& scenario, const std::string& out_dir, const std::optional<RunStats>& stats, double wall_s,
              std::uint64_t warnings_before, bool plots) const {
    const std::string summary = out_dir + "/summary.json";
    if (quiet_) {
      std::printf("%s\n", out_dir.c_str());
      return;
    }
    if (json_) {
      std::ifstream in(summary);
      if (!in) {
        if (!stats) {
          return;  // a failed run without one: its error line says why
        }
        throw RunError("--json: the run wrote no " + summary + " (the scenario has no evaluator)");
      }
      std::ostringstream text;
      text << in.rdbuf();
      std::fputs(text.str().c_str(), stdout);
      return;
    }
    if (verbose_) {
      if (stats) {
        std::printf("done: %llu ticks in %.3f s (%.0f ticks/s)\n", static_cast<unsigned long long>(stats->steps), stats->wall_s,
                    stats->wall_s > 0 ? static_cast<double>(stats->steps) / stats->wall_s : 0.0);
      }
      std::fputs(summary_table(out_dir).c_str(), stdout);
      std::printf("results: %s\n", out_dir.c_str());
      return;
    }
    RunReportInput in;
    if (std::ifstream(summary)) {
      try {
        in.summary = summary_leaves(summary);
        if (!stats) {  // failed: the error line after the report gives the reason
          in.summary.erase(std::remove_if(in.summary.begin(), in.summary.end(),
                                          [](const SummaryLeaf& leaf) { return leaf.path == "reason"; }),
                           in.summary.end());
        }
      } catch (const std::runtime_error& e) {
        in.summary_note = e.what();
      }
    } else {
      in.summary_note = "no summary.json in " + out_dir + ": the scenario has no evaluator";
    }
    in.headline = module_headlines();
    if (stats) {
      in.ticks = stats->steps;
    }
    in.wall_s = wall_s;
    in.step_s = scenario.step_s;
    in.warnings_logged = log::warnings_written() - warnings_before;
    in.out_dir = out_dir;
    in.csv_files = files_ending(out_dir, ".csv");
    in.plot_files = plots ? files_ending(out_dir, ".png") : 0;
    for (const std::string& line : run_report_lines(in)) {
      std::printf("%s\n", line.c_str());
    }
  }

  /// With --record: the recorder to add (and its parameters appended to the --set list, which
  /// every child host applies too); nothing otherwise.
  std::vector<std::string> record_components(const Scenario& scenario) {
    if (record_.empty()) {
      if (!record_topics_.empty() || record_compression_ != "zstd" || record_foxglove_scene_) {
        throw ConfigError("--record-topics, --record-compression and --record-foxglove-scene go with --record FILE.mcap");
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
    if (record_foxglove_scene_) {
      sets_.push_back(recorder + ".foxglove_scene=true");
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
  bool verbose_ = false;
  bool quiet_ = false;
  bool json_ = false;
  std::string record_;
  std::string record_compression_ = "zstd";
  std::vector<std::string> record_topics_;
  bool record_foxglove_scene_ = false;
  DdsArgs dds_;
  LockstepArgs lockstep_;
};

}  // namespace

std::unique_ptr<Command> add_run_command(CLI::App& app, const CommandEnv& env) { return std::make_unique<RunCommand>(app, env); }

}  // namespace robodds
