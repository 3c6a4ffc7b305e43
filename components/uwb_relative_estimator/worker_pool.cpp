#include "components/uwb_relative_estimator/worker_pool.hpp"

#include <stdexcept>
#include <string>

namespace robodds::uwb_relative_estimator {

WorkerPool::WorkerPool(int threads) {
  if (threads < 1) {
    throw std::invalid_argument("threads: must be >= 1 (got " + std::to_string(threads) + ")");
  }
  workers_.reserve(static_cast<std::size_t>(threads - 1));
  for (int t = 1; t < threads; ++t) {
    workers_.emplace_back([this] { work(); });
  }
}

WorkerPool::~WorkerPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& worker : workers_) {
    worker.join();
  }
}

void WorkerPool::run(std::size_t n, const std::function<void(std::size_t)>& task) {
  if (n == 0) {
    return;
  }
  if (workers_.empty()) {
    for (std::size_t i = 0; i < n; ++i) {
      task(i);  // an exception leaves at once: nothing else runs concurrently
    }
    return;
  }
  std::unique_lock<std::mutex> lock(mutex_);
  task_ = &task;
  count_ = n;
  next_ = 0;
  finished_ = 0;
  errors_.assign(n, nullptr);
  ++batch_;
  wake_.notify_all();
  drain(lock);
  done_.wait(lock, [this] { return finished_ == count_; });
  task_ = nullptr;
  for (const std::exception_ptr& error : errors_) {
    if (error) {
      std::rethrow_exception(error);
    }
  }
}

void WorkerPool::drain(std::unique_lock<std::mutex>& lock) {
  while (next_ < count_) {
    const std::size_t i = next_++;
    const std::function<void(std::size_t)>& task = *task_;
    lock.unlock();
    std::exception_ptr error;
    try {
      task(i);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    errors_[i] = error;
    if (++finished_ == count_) {
      done_.notify_one();
    }
  }
}

void WorkerPool::work() {
  std::size_t seen = 0;
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stop_ || batch_ != seen; });
    if (stop_) {
      return;
    }
    seen = batch_;
    drain(lock);
  }
}

}  // namespace robodds::uwb_relative_estimator
