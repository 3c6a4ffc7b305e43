#include "components/uwb_relative_estimator/worker_pool.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace robodds::uwb_relative_estimator {
namespace {

TEST(WorkerPool, RunsEveryTaskOnceAndWaitsForAll) {
  for (int threads : {1, 2, 4}) {
    WorkerPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    for (std::size_t n : {0u, 1u, 3u, 50u}) {
      for (int round = 0; round < 20; ++round) {  // batches one after the other reuse the workers
        std::vector<std::atomic<int>> calls(n);
        pool.run(n, [&](std::size_t i) {
          if (i % 7 == 0) {
            std::this_thread::sleep_for(std::chrono::microseconds(50));  // finishes after the others
          }
          calls[i].fetch_add(1);
        });
        for (std::size_t i = 0; i < n; ++i) {
          ASSERT_EQ(calls[i].load(), 1) << "threads " << threads << " n " << n << " task " << i;
        }
      }
    }
  }
}

TEST(WorkerPool, SpreadsTasksOverItsThreads) {
  WorkerPool pool(2);
  std::set<std::thread::id> seen;
  std::atomic<int> running{0};
  std::atomic<int> most{0};
  std::mutex mutex;
  pool.run(2, [&](std::size_t) {
    const int now = running.fetch_add(1) + 1;
    int previous = most.load();
    while (now > previous && !most.compare_exchange_weak(previous, now)) {
    }
    // Both tasks wait (up to 5 s) until the other has started: they must run side by side.
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (most.load() < 2 && std::chrono::steady_clock::now() < until) {
      std::this_thread::yield();
    }
    const std::lock_guard<std::mutex> lock(mutex);
    seen.insert(std::this_thread::get_id());
  });
  EXPECT_EQ(most.load(), 2);
  EXPECT_EQ(seen.size(), 2u);
}

TEST(WorkerPool, OneThreadRunsInOrderOnTheCaller) {
  WorkerPool pool(1);
  std::vector<std::size_t> order;
  const std::thread::id caller = std::this_thread::get_id();
  pool.run(5, [&](std::size_t i) {
    EXPECT_EQ(std::this_thread::get_id(), caller);
    order.push_back(i);
  });
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
}

TEST(WorkerPool, RethrowsATaskExceptionAfterTheOthersRan) {
  WorkerPool pool(3);
  std::atomic<int> ran{0};
  EXPECT_THROW(pool.run(10,
                        [&](std::size_t i) {
                          ran.fetch_add(1);
                          if (i == 4) {
                            throw std::runtime_error("task 4");
                          }
                        }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 10);
  ran = 0;
  pool.run(3, [&](std::size_t) { ran.fetch_add(1); });  // still usable
  EXPECT_EQ(ran.load(), 3);
}

TEST(WorkerPool, RejectsNoThread) { EXPECT_THROW(WorkerPool(0), std::invalid_argument); }

}  // namespace
}  // namespace robodds::uwb_relative_estimator
