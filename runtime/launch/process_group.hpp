#pragma once
// Child processes (the hosts of `robodds run --deploy processes`, the plotting script): spawned
// with a parent-death signal (no orphans even if the runner is killed), polled without
// blocking, and always reaped.

#include <chrono>
#include <cstdint>
#include <string>
#include <sys/types.h>
#include <vector>

namespace robodds {

class ProcessGroup {
 public:
  ~ProcessGroup();
  /// Starts `argv` as the process of group `name`; argv[0] is an executable path, or a name
  /// looked up in $PATH. A non-empty `log_file` takes the child's stdout and stderr (created or
  /// truncated; RunError naming it if it cannot be opened). The child starts on SCHED_OTHER
  /// unless `keep_scheduling` (a host of `robodds run --rt-priority`: it starts up at the
  /// runner's priority, before it applies its own; a helper such as python3 must not).
  /// `own_process_group`: the child leads a process group of its own (setpgid), so a terminal's
  /// Ctrl-C reaches the runner only, which decides what the child gets (signal_all), and starts
  /// with SIGUSR1 blocked until its handler unblocks it (a robodds host: tools/cli).
  void spawn(const std::string& name, const std::vector<std::string>& argv, const std::string& log_file = "",
             bool keep_scheduling = false, bool own_process_group = false);
  /// Sends `signal_number` with the value `value` (sigqueue: the child's SA_SIGINFO handler
  /// reads it from si_value) to every child still running.
  void signal_all(int signal_number, std::uint64_t value);
  /// Throws RunError naming the group if a child has failed (non-zero exit or a signal) while the
  /// run goes on; a child that ended with code 0 finished its part and is only reaped.
  void check_alive();
  /// Reaps children that exited; throws RunError naming a group that failed (non-zero exit or
  /// signal). Returns how many are still running.
  std::size_t reap_finished();
  /// Waits up to timeout_s for every child to exit; throws RunError naming a group that failed.
  void wait_all(double timeout_s);
  /// Exit code of the index-th spawned child (128 + signal if killed), -1 while it runs.
  int poll_exit_status(std::size_t index);
  /// SIGTERM, then SIGKILL after grace_s, then reaps.
  void terminate_all(double grace_s);

 private:
  struct Child {
    std::string name;
    pid_t pid = -1;
    bool exited = false;
    int status = 0;
  };
  std::string describe_exit(const Child& child) const;
  /// Waits (polling) until `child` has exited, at most until `deadline`; true if it has.
  static bool reap_by(Child& child, std::chrono::steady_clock::time_point deadline);
  std::vector<Child> children_;
};

/// Runs `argv` to its end and returns its exit code (128 + signal if killed; 127 if it cannot
/// be executed). After timeout_s it is terminated and RunError names `what` and the timeout. A
/// non-empty `log_file` takes its stdout and stderr (ProcessGroup::spawn).
int run_to_exit(const std::string& what, const std::vector<std::string>& argv, double timeout_s, const std::string& log_file = "");

}  // namespace robodds
