#pragma once
// A small fixed pool of worker threads for the relative estimator's per-peer work (issue 29): run(n,
// task) calls task(0) .. task(n - 1), each exactly once, spread over the workers and the calling
// thread, and returns when every call has returned. The tasks are taken in index order (put the
// longest first); which thread runs which task varies, so tasks must write disjoint state: then the
// results do not depend on the number of threads. With threads = 1 there is no worker: run() calls
// the tasks in order on the calling thread.
// Pure: std only.
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace robodds::uwb_relative_estimator {

class WorkerPool {
 public:
  /// `threads` >= 1 (the calling thread counts as one). Throws std::invalid_argument.
  explicit WorkerPool(int threads);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// Runs task(i) for every i < n and waits for all of them. An exception of a task is rethrown
  /// here after every task has run (the lowest index's when several threw). Not reentrant: one
  /// run() at a time, and not from inside a task.
  void run(std::size_t n, const std::function<void(std::size_t)>& task);

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

 private:
  void work();
  /// Takes and runs tasks of the current batch until none is left.
  void drain(std::unique_lock<std::mutex>& lock);

  std::mutex mutex_;
  std::condition_variable wake_;  // workers: a new batch, or stop
  std::condition_variable done_;  // run(): the last task of the batch returned
  const std::function<void(std::size_t)>* task_ = nullptr;
  std::size_t count_ = 0;     // tasks in the batch
  std::size_t next_ = 0;      // first task not taken yet
  std::size_t finished_ = 0;  // tasks returned
  std::size_t batch_ = 0;     // incremented per run(): a worker joins each batch once
  std::vector<std::exception_ptr> errors_;
  bool stop_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace robodds::uwb_relative_estimator
