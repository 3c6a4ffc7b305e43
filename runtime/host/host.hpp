#pragma once
// The generic host: runs a set of components in one process on one executor thread, in
// lockstep (optionally also acting as the coordinator that publishes ticks) or in real time.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "runtime/bus/run_digest.hpp"
#include "runtime/component/component.hpp"
#include "runtime/component/registry.hpp"

namespace robodds {

struct HostOptions {
  std::string member = "host";              // this host's group name (its acknowledgements)
  std::vector<std::string> components;      // component instances to run here
  std::uint64_t run_id = 1;                 // ticks of other runs are ignored
  bool coordinator = false;                 // also publish ticks and collect acknowledgements
  std::vector<std::string> members;         // groups the coordinator waits for
  double input_timeout_s = 10.0;            // max wait for a component's inputs at one step
  double start_timeout_s = 30.0;            // max wait for the first tick / first acknowledgements; real time
                                            // across processes: for the other groups to be discovered (PeerWatch)
  double tick_timeout_s = 30.0;             // max wait between ticks (host) or for acks (coordinator)
  std::int64_t realtime_epoch_ns = 0;       // real time: wall clock of step 0 (0 = now)
  std::size_t lockstep_window = 1;          // coordinator: ticks outstanding at once (1 = strict)
  bool single_process = false;              // this host runs the whole scenario (RunContext::single_process)
  /// Lockstep, coordinator and components in this host (a co-located `robodds run`): ticks and
  /// acknowledgements go between its two halves through an in-memory bus of its own, not DDS
  /// (sim/clock and sim/step_done then stay inside the process). Same protocol, same Inputs.
  bool lockstep_in_memory = false;
  /// Lockstep: what the "no tick on sim/clock" error asks or advises (empty: whether the
  /// coordinator, robodds run, is alive and on the same domain). Set by the launcher, which
  /// knows how this host was started (e.g. a component executable without a scenario).
  std::string no_tick_advice;
  std::function<void()> poll;               // called every loop iteration; may throw (child died)
  std::function<void(std::uint64_t step, std::uint64_t last_step)> progress;
  const std::atomic<bool>* stop = nullptr;  // set by a signal handler
  /// Real time: `stop` ends the run normally (components finish, no error) instead of
  /// interrupting it. For hosts that run until stopped (a component executable on a robot).
  bool stop_ends_run = false;
  /// Real time: once set (the first SIGINT/SIGTERM of `robodds run --realtime`), the run ends
  /// cleanly after the step it is at, as at its end (on_finish, health, summary "completed" with
  /// RunFigures::stopped_by); `stop` (the second signal) still aborts.
  const std::atomic<bool>* graceful_stop = nullptr;
  /// Real time: once not kNoStopStep, the run ends cleanly after this step (or at once if past
  /// it): the step the runner of --deploy processes chose for every child host, so that they
  /// all end together, as at a normal end.
  const std::atomic<std::uint64_t>* stop_at_step = nullptr;
  /// Real time: the run fails (RunError) when more due steps than this are skipped; nullopt:
  /// default_max_missed_steps() of the run's steps (runtime/health/overrun_counter.hpp).
  std::optional<std::uint64_t> max_missed_steps;
  /// What this host loaded (scenario, options, QoS files), announced to the other hosts of the run;
  /// a host of this run that announces another one fails a lockstep run, and in real time makes
  /// the outnumbered host refuse to start and the others run degraded (runtime/host/digest_check.hpp).
  /// Empty: not compared (co-located, a component without a scenario file).
  RunDigest digest;
};

/// HostOptions::stop_at_step before a stop was asked for.
inline constexpr std::uint64_t kNoStopStep = ~std::uint64_t{0};

struct RunStats {
  std::uint64_t steps = 0;  // ticks completed
  double wall_s = 0.0;
  /// Real time: why this host ran degraded (PeerWatch: groups it never discovered); empty: not.
  std::string degraded;
  /// Real time: "signal" when a graceful stop ended the run before its end (steps: those run).
  std::string stopped_by;
};

/// Exit code of a host that ran to its end degraded (RunStats::degraded): not a failure, not a
/// clean run either. `robodds run --deploy processes` takes it from a child as a degraded end.
inline constexpr int kDegradedExitCode = 3;

class Host {
 public:
  Host(const ComponentRegistry& registry, RunContext run, HostOptions options);
  ~Host();
  Host(const Host&) = delete;
  Host& operator=(const Host&) = delete;

  /// Creates and configures the components (ConfigError on bad parameters or topics).
  void configure();
  /// Runs to the end of the scenario; RunError on a timeout, a failed peer or a signal.
  RunStats run();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace robodds
