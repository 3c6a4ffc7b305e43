#pragma once
// --rt-priority N: the real-time loop runs SCHED_FIFO at priority N, the process's other threads
// at N - 1 (communication_priority), and its memory is locked
// (mlockall), so a busy machine (other jobs, CPU hogs) cannot delay a real-time loop by
// preempting it or paging it out. Operating-system code, no DDS: applied at process start,
// before the DDS participant exists, so every thread Fast DDS creates later inherits the policy.

#include <cstdint>
#include <optional>
#include <string>

namespace robodds {

/// The command-line option every executable that applies it spells (errors name it).
inline constexpr const char* kRtPriorityOption = "--rt-priority";
/// SCHED_FIFO priorities Linux accepts (sched_get_priority_min/max(SCHED_FIFO)).
inline constexpr int kMinRtPriority = 1;
inline constexpr int kMaxRtPriority = 99;

/// Empty when `text` is a whole number kMinRtPriority..kMaxRtPriority, else why not (one phrase,
/// for the CLI validator and for rt_priority_from_text()).
std::string rt_priority_problem(const std::string& text);
/// The priority of `text`; ConfigError "--rt-priority TEXT: ..." when rt_priority_problem() has one.
int rt_priority_from_text(const std::string& text);

/// What decides whether the process may use SCHED_FIFO and lock its memory (for the messages).
struct RtPermissions {
  bool cap_sys_nice = false;  // effective CAP_SYS_NICE: any SCHED_FIFO priority
  bool cap_ipc_lock = false;  // effective CAP_IPC_LOCK: mlockall without a size limit
  std::optional<std::uint64_t> rtprio_limit;   // soft RLIMIT_RTPRIO; nullopt: unlimited
  std::optional<std::uint64_t> memlock_limit;  // soft RLIMIT_MEMLOCK (bytes); nullopt: unlimited
};
/// This process's capabilities (/proc/self/status CapEff) and resource limits.
RtPermissions current_rt_permissions();

/// The one-line reasons of a refusal (pure, for the tests): what was refused, why, what to do.
std::string sched_refusal(int priority, int error, const RtPermissions& permissions);
std::string mlock_refusal(int priority, int error, const RtPermissions& permissions);

/// The priority of every thread but the real-time loop's under --rt-priority N: one below N
/// (N = 1: 1 too). The loop outranks its own process's Fast DDS threads: SCHED_FIFO threads of
/// one priority never preempt each other, so at one priority a burst on a receive thread (a flood
/// of foreign keys, issue 24 finding 4) held the loop off its CPU until the burst ended (51 missed
/// steps in integration.key_flood beside eight CPU hogs). Both still outrank every SCHED_OTHER job.
int communication_priority(int priority);

/// SCHED_FIFO at communication_priority(`priority`) for every thread of this process (those that
/// exist now, and through inheritance every one created later) and mlockall(MCL_CURRENT |
/// MCL_FUTURE); the real-time loop raises its own thread to `priority` (raise_loop_thread()). ConfigError with
/// sched_refusal()/mlock_refusal() when the system refuses (nothing is left half applied: a
/// refused mlockall puts the threads back on their policy); ConfigError for a priority out of range.
/// Returns a warning for the caller to log (empty: none): memory locked under a finite
/// RLIMIT_MEMLOCK without CAP_IPC_LOCK, where MCL_FUTURE makes allocations past it fail.
std::string apply_rt_priority(int priority);

/// From a real-time loop's thread, once, before its first step: that thread to SCHED_FIFO at the
/// priority apply_rt_priority() was given (above this process's other threads). Nothing when
/// apply_rt_priority() did not run in this process. ConfigError with sched_refusal() if refused.
void raise_loop_thread();

/// The calling thread to the ordinary policy (SCHED_OTHER, nice unchanged): for threads that
/// write files (runtime/io/batch_writer_thread.hpp). Under --rt-priority a thread inherits
/// SCHED_FIFO from the thread that creates it (the loop), and a file writer at the loop's priority
/// would outrank the host's receive threads. Lowering needs no privilege; nothing when it is
/// already ordinary.
void lower_to_ordinary_priority();

}  // namespace robodds
