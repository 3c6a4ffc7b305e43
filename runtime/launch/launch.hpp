#pragma once
// Launching runs: a scenario's components in this process (co-located, or the share of one
// `robodds host`), or one child `robodds host` per deployment group with this process as the
// lockstep coordinator; plus the small process chores around a run (output directory, plots).
// The CLI only parses its options into these structs and calls these functions.

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "runtime/dds/dds_bus.hpp"
#include "runtime/host/host.hpp"
#include "runtime/host/producer_check.hpp"
#include "runtime/launch/host_args.hpp"
#include "runtime/launch/output_dir.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/config/scenario.hpp"

namespace robodds {

enum class Deploy { kColocated, kProcesses };

/// "colocated" / "processes": the --deploy value and the "deploy" of summary.json's run section.
const char* to_string(Deploy deploy);

/// What `robodds run` asks for.
struct LaunchOptions {
  std::string scenario_file;  // given to the child hosts (they load it themselves)
  std::vector<std::string> sets;  // --set assignments, already applied to the scenario; the child hosts apply them too
  std::vector<std::string> added_components;  // "GROUP:NAME:TYPE", already added to the scenario; the child hosts add them too
  Deploy deploy = Deploy::kColocated;
  bool realtime = false;      // wall-clock timers instead of lockstep
  std::string out_dir;        // where the evaluator writes
  DdsOptions dds;             // resolved; the child hosts get the same domain, profile and files
  LockstepArgs lockstep;
  std::string log_level;      // of the child hosts
  std::optional<std::uint64_t> max_missed_steps;  // real time: HostOptions::max_missed_steps of every host
  std::optional<int> rt_priority;  // --rt-priority of every child host (the caller applies it to itself: apply_rt_priority_option())
  std::function<void(std::uint64_t step, std::uint64_t last_step)> progress;
  const std::atomic<bool>* stop = nullptr;  // set by a signal handler: the run aborts (RunError)
  /// Real time: set by the first signal, the run stops cleanly at its next step (every host after
  /// the same step across processes: the runner sends it to them); `stop` then aborts.
  const std::atomic<bool>* graceful_stop = nullptr;
};

/// Real time across processes: how far ahead (s) of the runner's clock the step lies after which
/// every host ends on a graceful stop: the hosts get it within one loop iteration (at most 50 ms
/// of sleep), so they all reach it and end together, as at a normal end.
inline constexpr double kGracefulStopAheadS = 0.3;

/// The step every host ends after on a graceful stop asked for at wall time `now_ns` of a run
/// whose step 0 is at `epoch_ns`: kGracefulStopAheadS ahead, at least step 0.
std::uint64_t graceful_stop_step(std::int64_t epoch_ns, std::int64_t now_ns, double step_s);

/// --rt-priority of this process, if given: apply_rt_priority() before anything else starts (no
/// DDS participant yet, so every thread inherits it), its warning logged as `who`; ConfigError
/// (exit 2) when refused. `announce`: say so on the log (a host on its own, the runner).
void apply_rt_priority_option(const std::optional<int>& priority, const std::string& who, bool announce);

/// Runs `scenario` (already loaded, with the run's --seed and --duration applied) to its end.
/// The figures are this process's: the co-located host, the lockstep coordinator, or the wait
/// for the children of a real-time run across processes. ConfigError on bad input (checked
/// before any child starts), RunError on a failed or timed-out run.
RunStats launch_run(const ComponentRegistry& registry, const Scenario& scenario, const LaunchOptions& options);

/// `robodds host`: runs what `args` selects (a group, components, and/or the coordinator) in
/// this process until the run ends.
/// Returns the process's exit code: 0, or kDegradedExitCode when the host ran degraded (real time:
/// groups it never discovered); failures throw.
/// `stop`: aborts the run (a signal); `stop_at_step` (real time, may be null): a step other than
/// kNoStopStep ends the run cleanly after it (HostOptions::stop_at_step).
int run_host(const ComponentRegistry& registry, const HostArgs& args, const std::atomic<bool>* stop,
             const std::atomic<std::uint64_t>* stop_at_step = nullptr);

/// Where this process runs components: the bus, the run's context and its host.
struct InProcessRun {
  TimeMode mode = TimeMode::kLockstep;
  std::string out_dir;
  std::string deploy_label;  // non-empty: the run's recorder writes summary.json's "run" section
  /// Inputs accept an instance only from the producers the scenario assigns to it
  /// (RunContext::assigned_producers); false: the first writer rule (a component without a scenario).
  bool assign_producers = true;
  /// The scenario's producers (scenario_producers()) as the caller's start-up check found them;
  /// null: found here when needed.
  const ScenarioProducers* producers = nullptr;
};

/// Creates a DDS bus and a Host for `options.components` and runs them to the end.
RunStats run_in_process(const ComponentRegistry& registry, const Scenario& scenario, const DdsOptions& dds,
                        HostOptions options, const InProcessRun& run);

/// The DDS options of `args`, the environment filling what is not given:
/// $ROBODDS_DOMAIN_ID (ConfigError if not 0..232), $ROBODDS_QOS_FILE, $ROBODDS_PARTICIPANT_PROFILE.
DdsOptions resolve_dds(const DdsArgs& args, const std::string& participant_name);
/// resolve_dds() for `robodds topics/echo`: DDS Security identity `tools` (reads every topic, writes none).
DdsOptions tools_dds(const DdsArgs& args, const std::string& participant_name);

/// Repository root or install prefix: $ROBODDS_SHARE_DIR, else the source tree it was built from.
std::string share_dir();

/// Draws a run's plots: `python3 sim/report/report.py OUT_DIR` as a child process (stdout and
/// stderr shared, or both into `log_file` if given), waited for at most timeout_s. Returns the
/// script's exit code.
int draw_plots(const std::string& out_dir, double timeout_s = 600.0, const std::string& log_file = "");

}  // namespace robodds
