#include "runtime/health/shutdown_watchdog.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include <pthread.h>

#include "common/number_parse.hpp"
#include "runtime/base/log.hpp"

namespace robodds {
namespace {

std::atomic<bool> g_shutting_down{false};  // sticky: a signal between two steps must not be lost

}  // namespace

std::chrono::milliseconds shutdown_limit() {
  double seconds = kDefaultShutdownLimitS;
  if (const char* text = std::getenv("ROBODDS_SHUTDOWN_LIMIT_S"); text != nullptr && *text != '\0') {
    const std::optional<double> parsed = parse_finite_number(text);
    if (parsed && *parsed > 0.0) {
      seconds = *parsed;
    } else {
      log::warn("shutdown", std::string("ROBODDS_SHUTDOWN_LIMIT_S='") + text + "' is not a number of seconds > 0; using " +
                                std::to_string(kDefaultShutdownLimitS) + " s");
    }
  }
  return std::chrono::milliseconds(static_cast<long long>(std::llround(seconds * 1000.0)));
}

bool shutting_down() { return g_shutting_down.load(); }

ShutdownWatchdog::ShutdownWatchdog(std::string what, std::chrono::milliseconds limit)
    : what_(std::move(what)), limit_(limit) {
  g_shutting_down = true;
  thread_ = std::thread([this] { watch(); });
}

ShutdownWatchdog::~ShutdownWatchdog() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  done_cv_.notify_all();
  thread_.join();
}

void ShutdownWatchdog::watch() {
  pthread_setname_np(pthread_self(), kShutdownThreadName);  // visible in /proc/PID/task/*/comm
  std::unique_lock<std::mutex> lock(mutex_);
  if (done_cv_.wait_for(lock, limit_, [this] { return done_; })) {
    return;
  }
  // The stuck thread may hold locks a destructor or an atexit handler needs: leave at once.
  std::fprintf(stderr, "robodds: error: shutdown: %s did not finish within %.1f s; exiting with code %d\n", what_.c_str(),
               static_cast<double>(limit_.count()) / 1000.0, kShutdownTimeoutExit);
  std::fflush(stderr);
  std::_Exit(kShutdownTimeoutExit);
}

}  // namespace robodds
