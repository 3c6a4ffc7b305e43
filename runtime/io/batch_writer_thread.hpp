#pragma once
// Writing a run's files off the step's thread: batches of samples queued by the step, formatted
// and written by a thread of their own, in the order queued. Used by the run's recorder (MCAP)
// and the evaluator (CSV): both are on a lockstep step's critical path otherwise (the evaluator
// acknowledges a step only after it took and wrote every robot's samples of that step).

#include <pthread.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "runtime/base/error.hpp"
#include "runtime/base/realtime_priority.hpp"

namespace robodds {

/// One consumer thread for batches pushed by one producer thread, written in push order (the
/// file's order is the queue's). `Batch` has `std::size_t stream() const` (the producer's id for
/// the series it belongs to, from add_stream()) and `void clear()` (forgets the samples, keeps
/// the storage): a written batch is handed back by push() to be filled again, so a step
/// allocates nothing and the writer frees nothing the step allocated.
///
/// The writer is woken once kWakeAt batches wait (or by drain() and finish()), not for every
/// batch: waking a sleeping thread is a futex call, and one per topic and step was ~2 % of a
/// 200-robot co-located run's CPU (perf). At most `max_queued` batches wait: past that the producer
/// waits for the writer (a lockstep run loses nothing; its memory stays bounded when the writer is
/// the slower of the two, as in a fast co-located run). A wait for the writer gives up after
/// kStallTimeout with a RunError naming the owner (a stalled disk, not a slow one).
template <class Batch>
class BatchWriterThread {
 public:
  static constexpr std::size_t kWakeAt = 64;
  static constexpr std::chrono::seconds kStallTimeout{120};
  static constexpr const char* kThreadName = "robodds-files";  // at most 15 characters

  /// `owner`: names the files' writer in errors ("evaluator"). `write`: writes one batch, on the
  /// writer thread; what it throws stops the writer, and the producer's next push(), drain() or
  /// finish() throws it (once) as RunError("<owner>: <what>"). `max_queued` > kWakeAt.
  BatchWriterThread(std::string owner, std::function<void(Batch&)> write, std::size_t max_queued)
      : owner_(std::move(owner)), write_(std::move(write)), max_queued_(std::max(max_queued, kWakeAt + 1)),
        thread_([this] { loop(); }) {}
  BatchWriterThread(const BatchWriterThread&) = delete;
  BatchWriterThread& operator=(const BatchWriterThread&) = delete;
  ~BatchWriterThread() {
    try {
      finish();
    } catch (const std::exception&) {
      // said by an earlier call, or the run is being torn down after another error
    }
  }

  /// A new series id for batches (e.g. one per file); ids are 0, 1, ...
  std::size_t add_stream() {
    std::lock_guard<std::mutex> lock(mutex_);
    written_.emplace_back();
    return written_.size() - 1;
  }

  /// Queues `batch`; gives back a written batch of the same stream to fill next (null: none yet).
  /// After the writer failed, throws its error once and then drops (clears and gives back) what
  /// it is given.
  std::unique_ptr<Batch> push(std::unique_ptr<Batch> batch) {
    std::unique_lock<std::mutex> lock(mutex_);
    wait_locked(lock, room_, [this] { return queue_.size() < max_queued_ || failed_; }, "room in its queue");
    if (failed_) {
      rethrow_locked();
      batch->clear();
      return batch;
    }
    const std::size_t stream = batch->stream();
    queue_.push_back(std::move(batch));
    if (queue_.size() == kWakeAt) {
      ready_.notify_one();
    }
    if (stream >= written_.size() || written_[stream].empty()) {
      return nullptr;
    }
    std::unique_ptr<Batch> spare = std::move(written_[stream].back());
    written_[stream].pop_back();
    return spare;
  }

  /// Returns once every batch pushed so far is written; throws the writer's failure (once).
  void drain() {
    std::unique_lock<std::mutex> lock(mutex_);
    draining_ = true;
    ready_.notify_one();
    wait_locked(lock, idle_, [this] { return (queue_.empty() && !writing_) || failed_ || stopped_; },
                "the batches queued so far to be written");
    draining_ = false;
    rethrow_locked();
  }

  /// Writes what is queued and stops the thread; throws its failure (once).
  void finish() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
      ready_.notify_one();
    }
    if (thread_.joinable()) {
      thread_.join();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    rethrow_locked();
  }

 private:
  void loop() {
    lower_to_ordinary_priority();  // files are no real-time work (--rt-priority: inherited SCHED_FIFO)
    pthread_setname_np(pthread_self(), kThreadName);  // what ps and the rt_priority test see
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      ready_.wait(lock, [this] { return queue_.size() >= kWakeAt || done_ || (draining_ && !queue_.empty()); });
      if (queue_.empty()) {
        stopped_ = true;  // done, and everything written
        idle_.notify_all();
        return;
      }
      std::deque<std::unique_ptr<Batch>> taken;
      taken.swap(queue_);
      writing_ = true;
      room_.notify_all();
      lock.unlock();
      std::string error;
      try {
        for (const auto& batch : taken) {
          write_(*batch);
        }
      } catch (const std::exception& e) {
        error = e.what();
      }
      for (auto& batch : taken) {
        batch->clear();  // outside the lock: keeps the storage
      }
      lock.lock();
      writing_ = false;
      for (auto& batch : taken) {
        const std::size_t stream = batch->stream();
        if (written_.size() <= stream) {
          written_.resize(stream + 1);
        }
        written_[stream].push_back(std::move(batch));
      }
      if (!error.empty()) {
        failed_ = true;
        error_ = error;
        queue_.clear();
        room_.notify_all();
        idle_.notify_all();
        return;
      }
      idle_.notify_all();
    }
  }

  template <class Ready>
  void wait_locked(std::unique_lock<std::mutex>& lock, std::condition_variable& cv, Ready ready, const char* what) {
    if (!cv.wait_for(lock, kStallTimeout, ready)) {
      throw RunError(owner_ + ": waited " + std::to_string(kStallTimeout.count()) + " s for its writer thread (" + what +
                     "): is the output's disk stalled?");
    }
  }

  void rethrow_locked() {
    if (failed_ && !error_.empty()) {
      const std::string error = error_;
      error_.clear();  // said once
      throw RunError(owner_ + ": " + error);
    }
  }

  std::string owner_;
  std::function<void(Batch&)> write_;  // the writer thread's only
  std::size_t max_queued_;
  std::mutex mutex_;
  std::condition_variable ready_, room_, idle_;
  std::deque<std::unique_ptr<Batch>> queue_;
  // Written batches by stream, for push() to hand back: at most as many as were queued at once.
  std::vector<std::vector<std::unique_ptr<Batch>>> written_;
  bool done_ = false;
  bool draining_ = false;
  bool writing_ = false;
  bool failed_ = false;
  bool stopped_ = false;
  std::string error_;
  std::thread thread_;  // last: it starts once everything above exists
};

}  // namespace robodds
