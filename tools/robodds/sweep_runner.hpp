#pragma once
// `robodds sweep`: runs planned runs as `robodds run` child processes, `jobs` at a time, each
// worker slot on its own DDS domain so that concurrent runs never see each other's samples.

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "tools/robodds/sweep_results.hpp"

namespace robodds::sweep {

struct RunnerOptions {
  std::string robodds;        // the robodds executable
  std::string scenario_file;
  std::string out_dir;        // run k writes out_dir/runs/<k> (run_dir())
  std::size_t jobs = 1;       // worker slots
  int first_domain = 0;       // slot j runs on DDS domain first_domain + j
  double run_timeout_s = 3600.0;  // a run still going after this is killed and recorded as failed
  std::vector<std::string> run_args;  // appended to every `robodds run` (e.g. --duration 50)
  const std::atomic<bool>* stop = nullptr;  // set by a signal handler: running runs are terminated, none started
};

struct Progress {
  std::size_t done = 0;
  std::size_t failed = 0;
  std::size_t total = 0;
  double elapsed_s = 0.0;
};

/// out_dir/runs/<index, 4 digits or more>.
std::string run_dir(const std::string& out_dir, std::size_t index);

/// The command line of `run` on `domain`.
std::vector<std::string> run_argv(const RunnerOptions& options, const PlannedRun& run, int domain);

/// The outcome of a finished run from its exit code and its directory (summary.json, run.log): ok
/// only if it exited 0 and its summary.json says "status": "completed" (a failed run writes one too).
RunOutcome collect_outcome(const PlannedRun& run, int exit_code, double wall_s, const std::string& dir);

/// The outcome recorded in `dir`/outcome.json by run_all (--aggregate reads it back: a run of a
/// batch array task ends with code 0 whatever its simulation did). Without outcome.json: from
/// summary.json alone (RunOutcome::not_run if `dir` is missing).
RunOutcome recorded_outcome(const PlannedRun& run, const std::string& dir);

/// Runs every run of `runs` (a failed run is recorded and the sweep goes on) and returns their
/// outcomes in the order of `runs`. `progress` is called after each run and once a second between runs. Interrupted
/// (options.stop): the running runs are terminated and their folders removed; they and the runs
/// not started come back not_run (the caller writes the tables of what finished).
std::vector<RunOutcome> run_all(const std::vector<PlannedRun>& runs, const RunnerOptions& options,
                                const std::function<void(const Progress&)>& progress);

}  // namespace robodds::sweep
