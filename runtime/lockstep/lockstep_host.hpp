#pragma once
// The host side of the lockstep protocol: takes ticks from sim/clock, runs each component due
// at the tick once its inputs for that step are ready, and acknowledges the tick on
// sim/step_done. The Host calls step() in its loop, next to LockstepCoordinator::poll().

#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/bus/step_needs.hpp"
#include "runtime/host/digest_check.hpp"
#include "runtime/host/health_exchange.hpp"
#include "runtime/host/host.hpp"
#include "runtime/host/host_slot.hpp"

namespace robodds {

class LockstepHost {
 public:
  using Slots = std::vector<std::unique_ptr<host_detail::ComponentSlot>>;

  /// Subscribes to sim/clock and advertises sim/step_done on `protocol_bus` (run.bus, or the
  /// host's in-memory bus: HostOptions::lockstep_in_memory). `run`, `options`, `slots` and
  /// `protocol_bus` must outlive this object; run.figures is filled before the components finish.
  /// `health` (nullable): exchanges run/health at the final tick, before the components finish.
  LockstepHost(RunContext& run, const HostOptions& options, Slots& slots, Bus& protocol_bus,
               HealthExchange* health = nullptr);

  /// Starts the timeouts (start_timeout_s for the first tick) and the run's wall clock.
  void begin(host_detail::Clock::time_point start);
  /// One pass: takes the next tick when idle, runs the due components whose inputs are ready,
  /// acknowledges the tick once all of them ran (after on_finish() at the final tick). Returns
  /// whether anything happened. RunError when no tick or no input arrives in time.
  bool step();
  bool done() const { return done_; }
  /// Ticks acknowledged so far (the steps done).
  std::uint64_t steps_done() const { return steps_done_; }
  /// Tells the coordinator that this host stops, and why (a failed acknowledgement), and waits
  /// until the coordinator has acknowledged it (at most kFailureReportWait), so that the report
  /// is not lost with the process that exits next.
  /// `await_coordinator`: first wait for the coordinator's reader to match, at most the start
  /// timeout (a host that found at once that another loaded other files: a coordinator that
  /// starts later must still learn why this group stopped).
  void publish_failure(const std::string& error, bool await_coordinator = false);
  static constexpr std::chrono::milliseconds kFailureReportWait{2000};

 private:
  bool take_tick();
  bool run_due_components();
  /// `next_ack`: the step of this host's next acknowledgement (its sample's next_step).
  void publish_ack(std::uint64_t step, std::uint64_t components_run, const std::string& error, std::uint64_t next_ack);
  /// The first step after `step` at which this host has work: a component due, a history
  /// checkpoint, or the run's last step. It acknowledges only those (ack_ahead_): each
  /// acknowledgement announces the next, and the coordinator's ready() rule takes the steps
  /// between as done.
  std::uint64_t next_busy_step(std::uint64_t step) const;
  /// Notes in run_.figures when a third of the run's steps is done (RunFigures::thirds_done_at_s).
  void note_thirds();

  RunContext& run_;
  const HostOptions& options_;
  Slots& slots_;
  HealthExchange* health_;
  StepState state_;
  std::unique_ptr<Input<idl::SimTick>> tick_input_;
  std::shared_ptr<ReaderHandle> tick_reader_;
  std::shared_ptr<WriterHandle> ack_writer_;
  std::unique_ptr<Output<idl::StepDone>> ack_output_;

  host_detail::Clock::time_point start_;
  host_detail::Clock::time_point waiting_since_;  // for the next tick, or for inputs during a tick
  std::deque<idl::SimTick> tick_queue_;
  bool first_tick_ = true;
  bool tick_active_ = false;
  bool tick_is_final_ = false;
  std::uint64_t tick_step_ = 0;  // the tick being processed (or the last one)
  std::uint64_t components_run_ = 0;
  std::uint64_t steps_done_ = 0;
  bool done_ = false;
  /// Whether this host acknowledges only its busy steps (next_busy_step()): when it loaded the
  /// coordinator's scenario (a run digest: the same last step), else every step.
  bool ack_ahead_ = false;
  std::uint64_t next_ack_step_ = 0;  // the step the previous acknowledgement announced
  /// The steps at which some component is due or waits for its inputs (a history checkpoint):
  /// the union of the slots' StepNeeds read at delay 0; nullopt without slots (no step is busy).
  std::optional<StepNeeds> busy_steps_;
  /// Per slot (history_checkpoints() in the .cpp): every how many steps the host also waits for
  /// the slot's inputs without running it (0: never), and
  /// whether that wait is still open at the current tick.
  std::vector<std::uint64_t> checkpoint_steps_;
  std::vector<bool> checkpoint_pending_;
  DigestCheck digests_;  // hosts of this run that loaded other files end it
};

}  // namespace robodds
