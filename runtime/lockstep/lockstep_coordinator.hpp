#pragma once
// The coordinator side of the lockstep protocol: publishes ticks on sim/clock, at most
// `lockstep_window` of them unacknowledged, collects every member's acknowledgement on
// sim/step_done, and reports a failed group or a missing acknowledgement. The Host calls
// poll() in its loop, next to LockstepHost::step().

#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "robodds/idl/robodds.h"
#include "runtime/host/digest_check.hpp"
#include "runtime/host/host.hpp"
#include "runtime/host/host_slot.hpp"

namespace robodds {

class LockstepCoordinator {
 public:
  /// Subscribes to sim/step_done (acknowledgements of options.members) and advertises sim/clock
  /// on `protocol_bus` (run.bus, or the host's in-memory bus). `run`, `options` and
  /// `protocol_bus` must outlive this object.
  LockstepCoordinator(const RunContext& run, const HostOptions& options, Bus& protocol_bus);

  /// Starts the timeouts (start_timeout_s for the first acknowledgement).
  void begin(host_detail::Clock::time_point start);
  /// One pass: throws RunError for a member that reported a failure, counts the steps every
  /// member acknowledged (reporting progress), publishes ticks up to the window. Returns
  /// whether acknowledgements or ticks moved. RunError when an acknowledgement is overdue.
  bool poll();
  bool done() const { return done_; }
  /// Steps [0, acknowledged_steps()) are acknowledged by every member.
  std::uint64_t acknowledged_steps() const { return acked_steps_; }

 private:
  void publish_tick(std::uint64_t step, bool final_tick);
  /// Before step 0 counts as done, and before a member's failure is reported: waits (at most
  /// 0.5 s, PeerDirectory's wait) until every member's participant is discovered, whose
  /// announcement can come after its first sample, then compares their digests with this
  /// host's (RunConfigError on a difference).
  void check_digests_once_discovered();
  /// For the acknowledgement timeout: "group 'b' (...)" (`first_missing`, as the input names it),
  /// or, when several members are missing, "groups 'a' (...), 'c' (...)": every one of them, in
  /// the order of options.members, so that a coordinator of component executables names each
  /// member that was not started, not only the first.
  std::string missing_members(const std::string& first_missing) const;

  const RunContext& run_;
  const HostOptions& options_;
  StepState state_;
  std::unique_ptr<Output<idl::SimTick>> tick_output_;
  std::unique_ptr<Input<idl::StepDone>> ack_input_;
  std::shared_ptr<ReaderHandle> ack_reader_;

  struct NewestAck {
    std::uint64_t step = 0;       // the newest step the member acknowledged
    std::uint64_t covers_to = 0;  // the steps before this are done (its next_step: ack-ahead)
  };
  std::map<std::uint64_t, NewestAck> newest_ack_;  // member's instance key -> its newest acknowledgement
  std::uint64_t acked_steps_ = 0;
  std::uint64_t next_tick_ = 0;  // ticks [0, next_tick_) are sent
  host_detail::Clock::time_point ack_progress_at_;
  bool done_ = false;
  DigestCheck digests_;
};

}  // namespace robodds
