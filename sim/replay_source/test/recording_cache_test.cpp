// The per-process cache of decoded recordings: a second use of the same file and question loads
// nothing; a file rewritten in between (even with the same size within one clock tick), another
// question or another file loads again; a failed load stores nothing; the oldest entry goes first.
#include "sim/replay_source/node/recording_cache.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "tests/support/temp_file.hpp"

namespace robodds::replay_source {
namespace {

struct Counter {
  int loads = 0;
  std::function<std::shared_ptr<const int>()> load(int value) {
    return [this, value] {
      ++loads;
      return std::make_shared<const int>(value);
    };
  }
};

TEST(RecordingCache, TheSameFileAndQuestionLoadOnce) {
  const std::string path = test_support::write_test_file("a.mcap", "recording one");
  RecordingCache<int> cache(2);
  Counter c;
  EXPECT_EQ(*cache.get(path, "topics x", c.load(1)), 1);
  EXPECT_EQ(*cache.get(path, "topics x", c.load(2)), 1) << "the stored value, not a new load";
  EXPECT_EQ(c.loads, 1);
  EXPECT_EQ(*cache.get(path, "topics y", c.load(3)), 3) << "another question of the file loads";
  EXPECT_EQ(c.loads, 2);
}

TEST(RecordingCache, ARewrittenFileLoadsAgainEvenWithTheSameSize) {
  const std::string path = test_support::write_test_file("a.mcap", "recording one");
  RecordingCache<int> cache(2);
  Counter c;
  EXPECT_EQ(*cache.get(path, "q", c.load(1)), 1);
  test_support::write_test_file("a.mcap", "recording two");  // same size, likely the same mtime tick
  EXPECT_EQ(*cache.get(path, "q", c.load(2)), 2);
  EXPECT_EQ(*cache.get(path, "q", c.load(3)), 2);
  EXPECT_EQ(c.loads, 2);
}

TEST(RecordingCache, AFailedLoadStoresNothing) {
  const std::string path = test_support::write_test_file("a.mcap", "x");
  RecordingCache<int> cache(2);
  EXPECT_THROW(cache.get(path, "q", []() -> std::shared_ptr<const int> { throw std::runtime_error("bad"); }),
               std::runtime_error);
  Counter c;
  EXPECT_EQ(*cache.get(path, "q", c.load(4)), 4);
  EXPECT_EQ(c.loads, 1);
}

TEST(RecordingCache, AMissingFileIsLoadedEachTimeSoTheReaderSaysWhy) {
  RecordingCache<int> cache(2);
  Counter c;
  cache.get("/nonexistent/run.mcap", "q", c.load(1));
  cache.get("/nonexistent/run.mcap", "q", c.load(1));
  EXPECT_EQ(c.loads, 2);
}

TEST(RecordingCache, TheLeastRecentlyUsedEntryGoesFirst) {
  const std::string a = test_support::write_test_file("a.mcap", "a");
  const std::string b = test_support::write_test_file("b.mcap", "b");
  const std::string d = test_support::write_test_file("d.mcap", "d");
  RecordingCache<int> cache(2);
  Counter c;
  cache.get(a, "q", c.load(1));
  cache.get(b, "q", c.load(2));
  cache.get(a, "q", c.load(1));  // a used last: b is the oldest
  cache.get(d, "q", c.load(3));  // b goes
  EXPECT_EQ(c.loads, 3);
  cache.get(a, "q", c.load(1));
  EXPECT_EQ(c.loads, 3) << "a was kept";
  cache.get(b, "q", c.load(2));
  EXPECT_EQ(c.loads, 4) << "b was evicted";
}

TEST(FileStamp, ChangesWithTheContentOfTheTail) {
  const std::string path = test_support::write_test_file("s.mcap", std::string(10000, 'a'));
  const auto one = file_stamp(path);
  ASSERT_TRUE(one.has_value());
  EXPECT_EQ(one->size, 10000u);
  EXPECT_TRUE(*one == *file_stamp(path));
  test_support::write_test_file("s.mcap", std::string(9999, 'a') + "b");
  EXPECT_FALSE(*one == *file_stamp(path));
  EXPECT_FALSE(file_stamp("/nonexistent/run.mcap").has_value());
}

}  // namespace
}  // namespace robodds::replay_source
