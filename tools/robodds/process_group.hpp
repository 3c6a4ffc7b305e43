#pragma once
// Child host processes of `robodds run --deploy processes`: spawned with a parent-death signal
// (no orphans even if the runner is killed), polled without blocking, and always reaped.

#include <string>
#include <sys/types.h>
#include <vector>

namespace robodds {

class ProcessGroup {
 public:
  ~ProcessGroup();
  /// Starts `argv` (argv[0] = executable path) as the process of group `name`.
  void spawn(const std::string& name, const std::vector<std::string>& argv);
  /// Throws RunError naming the group if a child has exited before being expected to.
  void check_alive();
  /// Reaps children that exited; throws RunError naming a group that failed (non-zero exit or
  /// signal). Returns how many are still running.
  std::size_t reap_finished();
  /// Waits up to timeout_s for every child to exit; throws RunError naming a group that failed.
  void wait_all(double timeout_s);
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
  std::vector<Child> children_;
};

}  // namespace robodds
