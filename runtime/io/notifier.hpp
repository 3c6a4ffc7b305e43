#pragma once
// Wakes the host's executor thread when a sample arrives (listener threads only notify).

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace robodds {

class Notifier {
 public:
  void notify() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++generation_;
    }
    cv_.notify_all();
  }
  std::uint64_t generation() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return generation_;
  }
  /// Waits until notify() was called after `seen` was read, or the timeout passes.
  void wait(std::uint64_t seen, std::chrono::microseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait_for(lock, timeout, [&] { return generation_ != seen; });
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::uint64_t generation_ = 0;
};

}  // namespace robodds
