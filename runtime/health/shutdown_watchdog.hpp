#pragma once
// Bounds a shutdown step that can block inside a library we do not control (deleting DDS
// entities: Fast DDS waits there for its own threads and locks, with no timeout of its own).
// Nothing may hang (docs/architecture.md, "Failure behaviour"): if the step has not finished
// within its limit, one line names it and the process ends with kShutdownTimeoutExit.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace robodds {

/// Exit code of a process whose shutdown step overran its limit (distinct from 0/1/2/130).
constexpr int kShutdownTimeoutExit = 3;
/// Name of the watchdog's thread (tests see from /proc that a process is in a watched step).
constexpr const char* kShutdownThreadName = "shutdown-watch";
/// Default limit of one watched step; ROBODDS_SHUTDOWN_LIMIT_S (seconds, > 0) overrides it.
constexpr double kDefaultShutdownLimitS = 10.0;

/// The limit of a watched step: ROBODDS_SHUTDOWN_LIMIT_S if set (bad value: one warning, default).
std::chrono::milliseconds shutdown_limit();

/// True once a ShutdownWatchdog was created: the process is tearing down, so a SIGINT/SIGTERM must
/// end it at once (tools/cli) instead of only asking a run loop, which has already returned, to
/// stop. It stays true between two watched steps, so that a signal arriving there is not lost.
bool shutting_down();

class ShutdownWatchdog {
 public:
  /// `what` says what the step waits for ("deleting the DDS participant 'x' ...").
  explicit ShutdownWatchdog(std::string what, std::chrono::milliseconds limit = shutdown_limit());
  ~ShutdownWatchdog();  // the step finished in time: stops the watch
  ShutdownWatchdog(const ShutdownWatchdog&) = delete;
  ShutdownWatchdog& operator=(const ShutdownWatchdog&) = delete;

 private:
  void watch();

  std::string what_;
  std::chrono::milliseconds limit_;
  std::mutex mutex_;
  std::condition_variable done_cv_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace robodds
