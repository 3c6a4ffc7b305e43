#include "runtime/io/batch_writer_thread.hpp"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace robodds {
namespace {

struct NumberBatch {
  explicit NumberBatch(std::size_t s) : stream_id(s) {}
  std::size_t stream() const { return stream_id; }
  void clear() { numbers.clear(); }
  std::size_t stream_id;
  std::vector<int> numbers;
};

/// What the writer thread wrote, in order (read after drain()/finish()).
struct Written {
  std::mutex mutex;
  std::vector<int> numbers;
};

constexpr std::size_t kQueue = 4096;

std::unique_ptr<NumberBatch> batch_of(std::size_t stream, std::vector<int> numbers) {
  auto batch = std::make_unique<NumberBatch>(stream);
  batch->numbers = std::move(numbers);
  return batch;
}

TEST(BatchWriterThread, WritesEveryBatchInTheOrderPushedOnceDrained) {
  Written written;
  BatchWriterThread<NumberBatch> writer("test", [&](NumberBatch& b) {
    std::lock_guard<std::mutex> lock(written.mutex);
    written.numbers.insert(written.numbers.end(), b.numbers.begin(), b.numbers.end());
  }, kQueue);
  const std::size_t a = writer.add_stream();
  const std::size_t b = writer.add_stream();
  EXPECT_NE(a, b);
  std::vector<int> expected;
  for (int i = 0; i < 10; ++i) {  // fewer than kWakeAt: only drain() wakes the writer
    writer.push(batch_of(i % 2 == 0 ? a : b, {2 * i, 2 * i + 1}));
    expected.push_back(2 * i);
    expected.push_back(2 * i + 1);
  }
  writer.drain();
  {
    std::lock_guard<std::mutex> lock(written.mutex);
    EXPECT_EQ(written.numbers, expected);
  }
  writer.push(batch_of(a, {99}));
  writer.finish();  // writes what is queued
  expected.push_back(99);
  EXPECT_EQ(written.numbers, expected);
}

TEST(BatchWriterThread, HandsBackWrittenBatchesOfTheSameStreamCleared) {
  std::atomic<int> writes{0};
  BatchWriterThread<NumberBatch> writer("test", [&](NumberBatch&) { ++writes; }, kQueue);
  const std::size_t a = writer.add_stream();
  const std::size_t b = writer.add_stream();
  NumberBatch* first = nullptr;
  {
    auto batch = batch_of(a, {1, 2, 3});
    first = batch.get();
    EXPECT_EQ(writer.push(std::move(batch)), nullptr);  // nothing written yet
  }
  writer.drain();
  EXPECT_EQ(writer.push(batch_of(b, {4})), nullptr);  // stream b has no written batch
  std::unique_ptr<NumberBatch> spare = writer.push(batch_of(a, {5}));
  ASSERT_NE(spare, nullptr);
  EXPECT_EQ(spare.get(), first);
  EXPECT_EQ(spare->stream(), a);
  EXPECT_TRUE(spare->numbers.empty());
  writer.finish();
  EXPECT_EQ(writes.load(), 3);
}

TEST(BatchWriterThread, WakesTheWriterOnceEnoughBatchesWait) {
  std::atomic<int> writes{0};
  BatchWriterThread<NumberBatch> writer("test", [&](NumberBatch&) { ++writes; }, kQueue);
  const std::size_t a = writer.add_stream();
  for (std::size_t i = 0; i < BatchWriterThread<NumberBatch>::kWakeAt; ++i) {
    writer.push(batch_of(a, {1}));
  }
  // No drain(): the kWakeAt-th batch woke the writer.
  for (int i = 0; i < 500 && writes.load() < static_cast<int>(BatchWriterThread<NumberBatch>::kWakeAt); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(writes.load(), static_cast<int>(BatchWriterThread<NumberBatch>::kWakeAt));
}

TEST(BatchWriterThread, APushWaitsForTheWriterWhenMaxQueuedBatchesWait) {
  constexpr std::size_t kWake = BatchWriterThread<NumberBatch>::kWakeAt;
  std::atomic<bool> release{false};
  std::atomic<int> writes{0};
  BatchWriterThread<NumberBatch> writer("test", [&](NumberBatch&) {
    while (!release.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ++writes;
  }, kWake + 1);
  const std::size_t a = writer.add_stream();
  for (std::size_t i = 0; i < kWake; ++i) {
    writer.push(batch_of(a, {1}));  // the last one wakes the writer, which takes all and blocks
  }
  for (int i = 0; i < 500 && writes.load() == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));  // let it take them
  }
  for (std::size_t i = 0; i < kWake + 1; ++i) {
    writer.push(batch_of(a, {2}));  // fills the queue to its bound
  }
  std::atomic<bool> pushed{false};
  std::thread producer([&] {
    writer.push(batch_of(a, {3}));
    pushed = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(pushed.load()) << "a push into a full queue did not wait for the writer";
  release = true;
  producer.join();
  EXPECT_TRUE(pushed.load());
  writer.finish();
  EXPECT_EQ(writes.load(), static_cast<int>(2 * kWake + 2));
}

TEST(BatchWriterThread, AFailedWriteIsThrownOnceNamingTheOwnerAndLaterBatchesAreDropped) {
  std::atomic<int> writes{0};
  BatchWriterThread<NumberBatch> writer("evaluator", [&](NumberBatch& b) {
    ++writes;
    if (!b.numbers.empty() && b.numbers[0] < 0) {
      throw std::runtime_error("cannot write out.csv");
    }
  }, kQueue);
  const std::size_t a = writer.add_stream();
  writer.push(batch_of(a, {1}));
  writer.push(batch_of(a, {-1}));
  writer.push(batch_of(a, {2}));  // queued behind the failing one: never written
  try {
    writer.drain();
    FAIL() << "drain() did not throw the writer's failure";
  } catch (const RunError& e) {
    EXPECT_EQ(std::string(e.what()), "evaluator: cannot write out.csv");
  }
  EXPECT_EQ(writes.load(), 2);
  // Said once: what follows is dropped, given back cleared, and nothing waits.
  std::unique_ptr<NumberBatch> back = writer.push(batch_of(a, {3}));
  ASSERT_NE(back, nullptr);
  EXPECT_TRUE(back->numbers.empty());
  EXPECT_NO_THROW(writer.drain());
  EXPECT_NO_THROW(writer.finish());
  EXPECT_EQ(writes.load(), 2);
}

TEST(BatchWriterThread, TheWriterRunsAtTheOrdinaryPolicyWhenItsCreatorIsRealTime) {
  sched_param fifo{};
  fifo.sched_priority = 1;
  int old_policy = SCHED_OTHER;
  sched_param old_param{};
  pthread_getschedparam(pthread_self(), &old_policy, &old_param);
  if (pthread_setschedparam(pthread_self(), SCHED_FIFO, &fifo) != 0) {
    GTEST_SKIP() << "SCHED_FIFO not permitted here (no CAP_SYS_NICE, RLIMIT_RTPRIO 0)";
  }
  std::atomic<int> writer_policy{-1};
  {
    BatchWriterThread<NumberBatch> writer("test", [&](NumberBatch&) {
      int policy = -1;
      sched_param param{};
      pthread_getschedparam(pthread_self(), &policy, &param);
      writer_policy = policy;
    }, kQueue);
    writer.push(batch_of(writer.add_stream(), {1}));
    writer.finish();
  }
  pthread_setschedparam(pthread_self(), old_policy, &old_param);
  EXPECT_EQ(writer_policy.load(), SCHED_OTHER) << "a file writer inherited the real-time policy of the loop";
}

TEST(BatchWriterThread, ADrainAfterFinishReturnsAtOnce) {
  BatchWriterThread<NumberBatch> writer("test", [](NumberBatch&) {}, kQueue);
  writer.push(batch_of(writer.add_stream(), {1}));
  writer.finish();
  EXPECT_NO_THROW(writer.drain());
}

}  // namespace
}  // namespace robodds
