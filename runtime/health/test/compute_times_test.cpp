// ComputeTimes: per stage count, median, p99 by nearest rank and max; bad values ignored; the
// samples bounded by the cap (a reservoir beyond it); ScopedComputeTimer measures a scope.
#include "runtime/health/compute_times.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <thread>

namespace robodds {
namespace {

TEST(ComputeTimes, MedianP99ByNearestRankAndMaxPerStageInFirstAddedOrder) {
  ComputeTimes times;
  // 1..200 ms in a shuffled order: median (100 + 101) / 2, p99 = the 198th smallest.
  for (int i = 0; i < 200; ++i) {
    times.add_ms("window", static_cast<double>((i * 37) % 200 + 1));
  }
  times.add_ms("cycle", 3.0);
  times.add_ms("cycle", 1.0);
  times.add_ms("cycle", 2.0);
  EXPECT_EQ(times.samples_kept(), 203u);
  const auto s = times.summaries();
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].stage, "window");
  EXPECT_EQ(s[0].count, 200u);
  EXPECT_DOUBLE_EQ(s[0].median_ms, 100.5);
  EXPECT_DOUBLE_EQ(s[0].p99_ms, 198.0);
  EXPECT_DOUBLE_EQ(s[0].max_ms, 200.0);
  EXPECT_EQ(s[1].stage, "cycle");
  EXPECT_EQ(s[1].count, 3u);
  EXPECT_DOUBLE_EQ(s[1].median_ms, 2.0);
  EXPECT_DOUBLE_EQ(s[1].p99_ms, 3.0);  // ceil(0.99 * 3) = 3rd smallest
  EXPECT_DOUBLE_EQ(s[1].max_ms, 3.0);
}

TEST(ComputeTimes, NearestRankIsTheCeilOfPTimesN) {
  EXPECT_DOUBLE_EQ(nearest_rank_percentile({5.0}, 99.0), 5.0);
  std::vector<double> hundred;
  for (int i = 1; i <= 100; ++i) {
    hundred.push_back(i);
  }
  EXPECT_DOUBLE_EQ(nearest_rank_percentile(hundred, 99.0), 99.0);  // rank 99 exactly, not 100
  hundred.push_back(101.0);
  EXPECT_DOUBLE_EQ(nearest_rank_percentile(hundred, 99.0), 100.0);  // ceil(99.99) = 100
  EXPECT_DOUBLE_EQ(nearest_rank_percentile(hundred, 50.0), 51.0);   // ceil(50.5) = 51
  const std::vector<double> sixty(hundred.begin(), hundred.begin() + 60);
  EXPECT_DOUBLE_EQ(nearest_rank_percentile(sixty, 99.0), 60.0);  // ceil(59.4) = 60, not the nearest 59
}

TEST(ComputeTimes, NonFiniteAndNegativeValuesCountNothing) {
  ComputeTimes times;
  times.add_ms("pf", std::numeric_limits<double>::quiet_NaN());
  times.add_ms("pf", std::numeric_limits<double>::infinity());
  times.add_ms("pf", -0.5);
  EXPECT_TRUE(times.summaries().empty()) << "a stage with only bad values does not exist";
  times.add_ms("pf", 4.0);
  times.add_ms("pf", -std::numeric_limits<double>::infinity());
  times.add_ms("pf", 0.0);
  const auto s = times.summaries();
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].count, 2u);
  EXPECT_DOUBLE_EQ(s[0].median_ms, 2.0);
  EXPECT_DOUBLE_EQ(s[0].max_ms, 4.0);
}

TEST(ComputeTimes, BeyondTheCapAReservoirKeepsTheFiguresWhileCountAndMaxStayExact) {
  // Cap 1000, 100000 samples: 1..100000 ms in order. A reservoir is a uniform sample of all
  // of them (median ~50000, p99 ~99000); keeping the first 1000 would give ~500 and ~990.
  ComputeTimes times(1000);
  for (int i = 1; i <= 100000; ++i) {
    times.add_ms("uwb", static_cast<double>(i));
  }
  const auto s = times.summaries();
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].count, 100000u);
  EXPECT_EQ(times.samples_kept(), 1000u);
  EXPECT_DOUBLE_EQ(s[0].max_ms, 100000.0);
  EXPECT_NEAR(s[0].median_ms, 50000.0, 5000.0);
  EXPECT_NEAR(s[0].p99_ms, 99000.0, 1500.0);
}

TEST(ComputeTimes, ScopedTimerAddsTheTimeOfItsScope) {
  ComputeTimes times;
  {
    ScopedComputeTimer timer(times, "cycle");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const auto s = times.summaries();
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].stage, "cycle");
  EXPECT_EQ(s[0].count, 1u);
  EXPECT_GE(s[0].median_ms, 20.0);
  EXPECT_LT(s[0].median_ms, 2000.0);
}

}  // namespace
}  // namespace robodds
