#include "tools/robodds/sweep_runner.hpp"

#include <chrono>
#include <filesystem>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <thread>

#include "common/json_writer.hpp"
#include "common/number_text.hpp"
#include "runtime/base/error.hpp"
#include "runtime/launch/output_dir.hpp"
#include "runtime/launch/process_group.hpp"
#include "tools/robodds/summary_table.hpp"

namespace robodds::sweep {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point from, Clock::time_point to) { return std::chrono::duration<double>(to - from).count(); }

/// The last line of `log` that says "error:" (robodds' one error line), else its last line.
std::string last_error_line(const std::string& log) {
  std::ifstream in(log);
  std::string line;
  std::string last;
  std::string error;
  while (std::getline(in, line)) {
    if (!line.empty()) {
      last = line;
    }
    if (line.find("error:") != std::string::npos) {
      error = line;
    }
  }
  return error.empty() ? last : error;
}

/// summary.json's "status" ("completed" or "failed") among its leaves.
std::string summary_status(const std::vector<SummaryLeaf>& leaves) {
  for (const SummaryLeaf& leaf : leaves) {
    if (leaf.path == "status") {
      return leaf.json.size() >= 2 && leaf.json.front() == '"' ? leaf.json.substr(1, leaf.json.size() - 2) : leaf.json;
    }
  }
  return "missing";
}

void record_outcome(const RunOutcome& outcome, const std::string& dir) {
  JsonWriter w;
  w.begin_object();
  w.value("exit_code", static_cast<std::int64_t>(outcome.exit_code));
  w.value("wall_s", outcome.wall_s);
  w.value("error", outcome.error);
  w.end_object();
  std::ofstream(dir + "/outcome.json") << w.str() << "\n";
}

RunOutcome not_run(const PlannedRun& run, const std::string& why) {
  RunOutcome outcome;
  outcome.run = run;
  outcome.not_run = true;
  outcome.error = "not run (" + why + ")";
  return outcome;
}

struct Slot {
  std::unique_ptr<ProcessGroup> process;  // empty: idle
  std::size_t run = 0;
  Clock::time_point started;
};

}  // namespace

std::string run_dir(const std::string& out_dir, std::size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "%04zu", index);
  return out_dir + "/runs/" + name;
}

std::vector<std::string> run_argv(const RunnerOptions& options, const PlannedRun& run, int domain) {
  std::vector<std::string> argv = {options.robodds, "run", options.scenario_file, "--seed", std::to_string(run.seed),
                                   "--out", run_dir(options.out_dir, run.index), "--domain", std::to_string(domain),
                                   "--no-plots"};
  for (const std::string& s : run.sets) {
    argv.insert(argv.end(), {"--set", s});
  }
  argv.insert(argv.end(), options.run_args.begin(), options.run_args.end());
  return argv;
}

RunOutcome collect_outcome(const PlannedRun& run, int exit_code, double wall_s, const std::string& dir) {
  RunOutcome outcome;
  outcome.run = run;
  outcome.exit_code = exit_code;
  outcome.wall_s = wall_s;
  if (exit_code != 0) {
    outcome.error = "exit " + std::to_string(exit_code) + ": " + last_error_line(dir + "/run.log");
    return outcome;
  }
  try {
    const std::vector<SummaryLeaf> leaves = summary_leaves(dir + "/summary.json");  // read once: status and metrics
    const std::string status = summary_status(leaves);
    if (status != "completed") {
      outcome.error = dir + "/summary.json: status " + status;
      return outcome;
    }
    outcome.metrics = metrics_of(leaves);
    outcome.ok = true;
  } catch (const std::exception& e) {
    outcome.error = e.what();
  }
  return outcome;
}

RunOutcome recorded_outcome(const PlannedRun& run, const std::string& dir) {
  if (!std::filesystem::exists(dir)) {
    return not_run(run, dir + " missing");
  }
  const std::string recorded = dir + "/outcome.json";
  if (!std::filesystem::exists(recorded)) {  // still running, killed with its worker, or an older sweep
    RunOutcome outcome = collect_outcome(run, 0, 0.0, dir);
    if (!outcome.ok) {
      outcome.exit_code = -1;
      outcome.error = "no outcome.json in " + dir + " (running, or its worker died): " + outcome.error;
    }
    return outcome;
  }
  int exit_code = -1;
  double wall_s = 0.0;
  for (const SummaryLeaf& leaf : summary_leaves(recorded)) {
    if (leaf.path == "exit_code" && leaf.number) {
      exit_code = static_cast<int>(*leaf.number);
    } else if (leaf.path == "wall_s" && leaf.number) {
      wall_s = *leaf.number;
    }
  }
  return collect_outcome(run, exit_code, wall_s, dir);
}

std::vector<RunOutcome> run_all(const std::vector<PlannedRun>& runs, const RunnerOptions& options,
                                const std::function<void(const Progress&)>& progress) {
  std::vector<std::optional<RunOutcome>> outcomes(runs.size());
  std::vector<Slot> slots(std::max<std::size_t>(options.jobs, 1));
  const Clock::time_point start = Clock::now();
  Clock::time_point last_progress = start;
  Progress p;
  p.total = runs.size();
  std::size_t next = 0;
  while (p.done < runs.size()) {
    if (options.stop != nullptr && options.stop->load()) {
      for (Slot& slot : slots) {
        if (slot.process) {
          slot.process.reset();  // terminates the run (SIGTERM, then SIGKILL)
          // Half a run is no result: its folder goes, so --aggregate and --resume see it as not run.
          std::filesystem::remove_all(run_dir(options.out_dir, runs[slot.run].index));
        }
      }
      break;
    }
    bool changed = false;
    for (std::size_t j = 0; j < slots.size(); ++j) {
      if (options.stop != nullptr && options.stop->load()) {
        break;  // a run the signal ended too (exit 130) is not run, not failed: above, next round
      }
      Slot& slot = slots[j];
      if (slot.process) {
        int status = slot.process->poll_exit_status(0);
        const double wall_s = seconds_between(slot.started, Clock::now());
        const std::string dir = run_dir(options.out_dir, runs[slot.run].index);
        if (status < 0 && wall_s > options.run_timeout_s) {
          slot.process->terminate_all(2.0);
          status = slot.process->poll_exit_status(0);
          std::ofstream(dir + "/run.log", std::ios::app)
              << "robodds sweep: error: the run did not finish within " << shortest_text(options.run_timeout_s)
              << " s (--run-timeout) and was killed\n";
        }
        if (status < 0) {
          continue;
        }
        outcomes[slot.run] = collect_outcome(runs[slot.run], status, wall_s, dir);
        record_outcome(*outcomes[slot.run], dir);
        slot.process.reset();
        ++p.done;
        p.failed += outcomes[slot.run]->ok ? 0 : 1;
        changed = true;
      }
      if (!slot.process && next < runs.size()) {
        const PlannedRun& run = runs[next];
        const std::string dir = run_dir(options.out_dir, run.index);
        std::filesystem::remove_all(dir);  // a retried run (a batch engine's retry) starts clean
        make_output_dir(dir);
        slot.process = std::make_unique<ProcessGroup>();
        slot.process->spawn("run " + std::to_string(run.index), run_argv(options, run, options.first_domain + static_cast<int>(j)),
                            dir + "/run.log");
        slot.run = next++;
        slot.started = Clock::now();
      }
    }
    // At every finished run, and once a second between them: runs longer than the progress
    // period still show a sign of life (the caller paces the lines).
    const Clock::time_point now = Clock::now();
    if (changed || now - last_progress >= std::chrono::seconds(1)) {
      last_progress = now;
      p.elapsed_s = seconds_between(start, now);
      progress(p);
    }
    if (!changed) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  std::vector<RunOutcome> out;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    out.push_back(outcomes[i] ? std::move(*outcomes[i]) : not_run(runs[i], "the sweep was interrupted"));
  }
  return out;
}

}  // namespace robodds::sweep
