#include "runtime/launch/process_group.hpp"

#include <sched.h>

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <cstring>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "common/number_text.hpp"
#include "runtime/host/host.hpp"
#include "runtime/base/log.hpp"
#include "runtime/base/error.hpp"

namespace robodds {
namespace {

std::chrono::steady_clock::time_point deadline_after(double seconds) {
  return std::chrono::steady_clock::now() +
         std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

ProcessGroup::~ProcessGroup() { terminate_all(2.0); }

void ProcessGroup::spawn(const std::string& name, const std::vector<std::string>& argv, const std::string& log_file,
                         bool keep_scheduling, bool own_process_group) {
  int log_fd = -1;
  if (!log_file.empty()) {
    log_fd = open(log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (log_fd < 0) {
      throw RunError("cannot open the log " + log_file + " of '" + name + "': " + std::strerror(errno));
    }
  }
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    const int error = errno;
    if (log_fd >= 0) {
      close(log_fd);
    }
    throw RunError("cannot start the process of group '" + name + "': " + std::strerror(error));
  }
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) {
      _exit(1);  // the runner died between fork and prctl
    }
    if (own_process_group) {
      setpgid(0, 0);
      // The runner's stop step (signal_all(SIGUSR1)) must not kill a host still loading (the
      // default action): it waits, pending across exec, until the host's handler unblocks it
      // (tools/cli install_stop_handlers()).
      sigset_t usr1;
      sigemptyset(&usr1);
      sigaddset(&usr1, SIGUSR1);
      sigprocmask(SIG_BLOCK, &usr1, nullptr);
    }
    if (!keep_scheduling) {
      // A helper (the plots' python3) does not inherit the runner's SCHED_FIFO (--rt-priority).
      const sched_param normal{};
      sched_setscheduler(0, SCHED_OTHER, &normal);
    }
    if (log_fd >= 0 && (dup2(log_fd, STDOUT_FILENO) < 0 || dup2(log_fd, STDERR_FILENO) < 0)) {
      _exit(126);
    }
    std::vector<char*> args;
    for (const std::string& a : argv) {
      args.push_back(const_cast<char*>(a.c_str()));
    }
    args.push_back(nullptr);
    execvp(args[0], args.data());
    std::fprintf(stderr, "[error] cannot execute %s: %s\n", args[0], std::strerror(errno));
    _exit(127);
  }
  if (log_fd >= 0) {
    close(log_fd);
  }
  children_.push_back(Child{name, pid, false, 0});
}

std::string ProcessGroup::describe_exit(const Child& child) const {
  if (WIFSIGNALED(child.status)) {
    return "was killed by signal " + std::to_string(WTERMSIG(child.status)) + " (" + strsignal(WTERMSIG(child.status)) + ")";
  }
  return "exited with code " + std::to_string(WEXITSTATUS(child.status));
}

void ProcessGroup::check_alive() {
  for (Child& child : children_) {
    if (child.exited) {
      continue;
    }
    if (waitpid(child.pid, &child.status, WNOHANG) == child.pid) {
      child.exited = true;
      if (WIFEXITED(child.status) && (WEXITSTATUS(child.status) == 0 || WEXITSTATUS(child.status) == kDegradedExitCode)) {
        // A host that ran its last step and sent its health may end before the coordinator has
        // finished with the other groups (nothing delays its exit). One that left early without
        // failing would miss its acknowledgements: the lockstep timeout names it.
        continue;
      }
      throw RunError("group '" + child.name + "' (pid " + std::to_string(child.pid) + ") " + describe_exit(child) +
                     " before the run finished");
    }
  }
}

std::size_t ProcessGroup::reap_finished() {
  std::size_t running = 0;
  for (Child& child : children_) {
    if (!child.exited && waitpid(child.pid, &child.status, WNOHANG) == child.pid) {
      child.exited = true;
      if (WIFEXITED(child.status) && WEXITSTATUS(child.status) == kDegradedExitCode) {
        // It ran to its end without some of its peers: its report (or its absence) makes
        // summary.json "degraded"; the run goes on.
        log::warn("run", "group '" + child.name + "' ended degraded (exit code " + std::to_string(kDegradedExitCode) +
                             "; its log says why)");
      } else if (!WIFEXITED(child.status) || WEXITSTATUS(child.status) != 0) {
        throw RunError("group '" + child.name + "' (pid " + std::to_string(child.pid) + ") " + describe_exit(child));
      }
    }
    running += child.exited ? 0 : 1;
  }
  return running;
}

void ProcessGroup::wait_all(double timeout_s) {
  const auto deadline = deadline_after(timeout_s);
  for (Child& child : children_) {
    if (!reap_by(child, deadline)) {
      throw RunError("group '" + child.name + "' (pid " + std::to_string(child.pid) + ") did not exit within " +
                     std::to_string(static_cast<int>(timeout_s)) + " s after the run");
    }
    if (!WIFEXITED(child.status) || WEXITSTATUS(child.status) != 0) {
      throw RunError("group '" + child.name + "' " + describe_exit(child));
    }
  }
}

int run_to_exit(const std::string& what, const std::vector<std::string>& argv, double timeout_s, const std::string& log_file) {
  ProcessGroup group;  // terminates the child if anything below throws
  group.spawn(what, argv, log_file);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (true) {
    const int status = group.poll_exit_status(0);
    if (status >= 0) {
      return status;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      throw RunError(what + " did not finish within " + shortest_text(timeout_s) + " s");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

int ProcessGroup::poll_exit_status(std::size_t index) {
  Child& child = children_.at(index);
  if (!child.exited && waitpid(child.pid, &child.status, WNOHANG) == child.pid) {
    child.exited = true;
  }
  if (!child.exited) {
    return -1;
  }
  return WIFSIGNALED(child.status) ? 128 + WTERMSIG(child.status) : WEXITSTATUS(child.status);
}

void ProcessGroup::signal_all(int signal_number, std::uint64_t value) {
  sigval carried{};
  carried.sival_ptr = reinterpret_cast<void*>(static_cast<std::uintptr_t>(value));
  for (const Child& child : children_) {
    if (!child.exited) {
      sigqueue(child.pid, signal_number, carried);
    }
  }
}

void ProcessGroup::terminate_all(double grace_s) {
  for (Child& child : children_) {
    if (!child.exited) {
      kill(child.pid, SIGTERM);
    }
  }
  const auto deadline = deadline_after(grace_s);
  for (Child& child : children_) {
    if (!reap_by(child, deadline)) {
      kill(child.pid, SIGKILL);
      waitpid(child.pid, &child.status, 0);
      child.exited = true;
    }
  }
}

bool ProcessGroup::reap_by(Child& child, std::chrono::steady_clock::time_point deadline) {
  while (!child.exited) {
    if (waitpid(child.pid, &child.status, WNOHANG) == child.pid) {
      child.exited = true;
    } else if (std::chrono::steady_clock::now() > deadline) {
      return false;
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  return true;
}

}  // namespace robodds
