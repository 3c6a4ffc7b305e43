#include "runtime/base/realtime_priority.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/types.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "common/number_parse.hpp"
#include "runtime/base/error.hpp"

namespace robodds {
namespace {

constexpr int kCapIpcLock = 14;  // linux/capability.h
constexpr int kCapSysNice = 23;

std::string option_with(int priority) { return std::string(kRtPriorityOption) + " " + std::to_string(priority); }

std::optional<std::uint64_t> soft_limit(int resource) {
  rlimit limit{};
  if (getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) {
    return std::nullopt;
  }
  return static_cast<std::uint64_t>(limit.rlim_cur);
}

std::string limit_text(const std::optional<std::uint64_t>& limit) { return limit ? std::to_string(*limit) : "unlimited"; }

/// Ids of this process's threads (/proc/self/task), the calling one included.
std::vector<pid_t> thread_ids() {
  std::vector<pid_t> ids;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task", error)) {
    const std::optional<std::uint64_t> id = parse_whole_number(entry.path().filename().string(), 0x7fffffff);
    if (id) {
      ids.push_back(static_cast<pid_t>(*id));
    }
  }
  return ids;
}

}  // namespace

std::string rt_priority_problem(const std::string& text) {
  const std::optional<std::uint64_t> value = parse_whole_number(text, kMaxRtPriority);
  if (!value || *value < static_cast<std::uint64_t>(kMinRtPriority)) {
    return "must be a whole number " + std::to_string(kMinRtPriority) + ".." + std::to_string(kMaxRtPriority) +
           " (the SCHED_FIFO priority; " + std::to_string(kMaxRtPriority) + " is the highest)";
  }
  return {};
}

int rt_priority_from_text(const std::string& text) {
  const std::string problem = rt_priority_problem(text);
  if (!problem.empty()) {
    throw ConfigError(std::string(kRtPriorityOption) + " " + text + ": " + problem);
  }
  return static_cast<int>(*parse_whole_number(text, kMaxRtPriority));
}

RtPermissions current_rt_permissions() {
  RtPermissions permissions;
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("CapEff:", 0) == 0) {
      const std::uint64_t caps = std::strtoull(line.c_str() + 7, nullptr, 16);
      permissions.cap_sys_nice = ((caps >> kCapSysNice) & 1U) != 0;
      permissions.cap_ipc_lock = ((caps >> kCapIpcLock) & 1U) != 0;
    }
  }
  permissions.rtprio_limit = soft_limit(RLIMIT_RTPRIO);
  permissions.memlock_limit = soft_limit(RLIMIT_MEMLOCK);
  return permissions;
}

std::string sched_refusal(int priority, int error, const RtPermissions& p) {
  std::string why;
  if (!p.cap_sys_nice) {
    why = "no CAP_SYS_NICE and RLIMIT_RTPRIO " + limit_text(p.rtprio_limit);
  } else {
    // With the capability the kernel still refuses a task in a cgroup without real-time runtime.
    why = std::string(std::strerror(error)) + " although CAP_SYS_NICE is held: a cgroup without real-time runtime (cpu.rt_runtime_us)?";
  }
  return option_with(priority) + ": SCHED_FIFO refused (" + why +
         "): run as root, give the capability (setcap cap_sys_nice,cap_ipc_lock+ep; docker: cap_add SYS_NICE), "
         "or raise rtprio to at least " + std::to_string(priority) + " in /etc/security/limits.conf";
}

std::string mlock_refusal(int priority, int error, const RtPermissions& p) {
  std::string why = std::strerror(error);
  if (!p.cap_ipc_lock) {
    why += "; no CAP_IPC_LOCK and RLIMIT_MEMLOCK " + limit_text(p.memlock_limit) + (p.memlock_limit ? " bytes" : "");
  }
  return option_with(priority) + ": locking the memory (mlockall) refused (" + why +
         "): run as root, give the capability (setcap cap_ipc_lock+ep; docker: cap_add IPC_LOCK), "
         "or set memlock unlimited in /etc/security/limits.conf";
}

int communication_priority(int priority) { return priority > kMinRtPriority ? priority - 1 : kMinRtPriority; }

namespace {
int applied_priority = 0;  // the --rt-priority this process applied (0: none); set once at start-up
}  // namespace

void raise_loop_thread() {
  if (applied_priority == 0) {
    return;
  }
  sched_param param{};
  param.sched_priority = applied_priority;
  if (sched_setscheduler(0, SCHED_FIFO, &param) != 0) {
    throw ConfigError(sched_refusal(applied_priority, errno, current_rt_permissions()));
  }
}

std::string apply_rt_priority(int priority) {
  if (priority < kMinRtPriority || priority > kMaxRtPriority) {
    throw ConfigError(option_with(priority) + ": " + rt_priority_problem(std::to_string(priority)));
  }
  const int old_policy = sched_getscheduler(0);
  sched_param old_param{};
  sched_getparam(0, &old_param);
  sched_param param{};
  param.sched_priority = communication_priority(priority);
  // The calling thread first: a thread it creates from now on inherits the policy (Fast DDS 2.9
  // starts its threads with default attributes, PTHREAD_INHERIT_SCHED). Then any thread that
  // already runs (sched_setscheduler acts on one thread on Linux, not on the process).
  if (sched_setscheduler(0, SCHED_FIFO, &param) != 0) {
    throw ConfigError(sched_refusal(priority, errno, current_rt_permissions()));
  }
  for (const pid_t tid : thread_ids()) {
    if (sched_setscheduler(tid, SCHED_FIFO, &param) != 0 && errno != ESRCH) {  // ESRCH: it just ended
      throw ConfigError(sched_refusal(priority, errno, current_rt_permissions()));
    }
  }
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    const int error = errno;
    for (const pid_t tid : thread_ids()) {
      sched_setscheduler(tid, old_policy, &old_param);  // back to what it was: nothing half applied
    }
    throw ConfigError(mlock_refusal(priority, error, current_rt_permissions()));
  }
  applied_priority = priority;
  const RtPermissions permissions = current_rt_permissions();
  if (!permissions.cap_ipc_lock && permissions.memlock_limit) {
    // MCL_FUTURE counts every later mapping (thread stacks, DDS buffers) against the limit:
    // past it, an allocation fails instead of being paged in.
    return option_with(priority) + ": memory locked under RLIMIT_MEMLOCK " + limit_text(permissions.memlock_limit) +
           " bytes without CAP_IPC_LOCK: allocations past it will fail; set memlock unlimited";
  }
  return {};
}

void lower_to_ordinary_priority() {
  int policy = SCHED_OTHER;
  sched_param param{};
  if (pthread_getschedparam(pthread_self(), &policy, &param) != 0 || policy == SCHED_OTHER) {
    return;
  }
  param.sched_priority = 0;
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &param);
}

}  // namespace robodds
