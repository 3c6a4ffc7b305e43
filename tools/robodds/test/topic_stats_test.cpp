#include "tools/robodds/topic_stats.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace robodds {
namespace {

constexpr std::int64_t kMs = 1000000;  // ns

ArrivalWindow window_of(std::size_t capacity, const std::vector<std::int64_t>& times_ns, std::size_t bytes = 76) {
  ArrivalWindow w(capacity);
  for (std::int64_t t : times_ns) {
    w.add(Arrival{t, bytes});
  }
  return w;
}

TEST(TopicStats, AWindowNeedsTwoSamples) {
  EXPECT_THROW(ArrivalWindow(1), std::invalid_argument);
  EXPECT_FALSE(period_stats(window_of(10, {})).has_value());
  EXPECT_FALSE(period_stats(window_of(10, {5 * kMs})).has_value());
  EXPECT_FALSE(size_stats(window_of(10, {5 * kMs})).has_value());
  // Two at one instant: no period to take a rate from.
  EXPECT_FALSE(period_stats(window_of(10, {5 * kMs, 5 * kMs})).has_value());
}

TEST(TopicStats, EvenPeriodsGiveTheirRateAndNoSpread) {
  // 11 samples 10 ms apart: 100 Hz, every period 10 ms.
  std::vector<std::int64_t> t;
  for (int i = 0; i <= 10; ++i) t.push_back(1'700'000'000'000'000'000 + i * 10 * kMs);
  const auto s = period_stats(window_of(100, t));
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->messages, 11u);
  EXPECT_NEAR(s->rate_hz, 100.0, 1e-9);
  EXPECT_NEAR(s->mean_s, 0.010, 1e-12);
  EXPECT_NEAR(s->min_s, 0.010, 1e-12);
  EXPECT_NEAR(s->max_s, 0.010, 1e-12);
  EXPECT_NEAR(s->std_s, 0.0, 1e-12);
}

TEST(TopicStats, UnevenPeriodsGiveMeanExtremesAndPopulationStd) {
  // Periods 10, 30, 20 ms: mean 20 ms (50 Hz), std sqrt((100 + 100 + 0) / 3) ms, as ros2 topic hz.
  const auto s = period_stats(window_of(100, {0, 10 * kMs, 40 * kMs, 60 * kMs}));
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->rate_hz, 50.0, 1e-9);
  EXPECT_NEAR(s->min_s, 0.010, 1e-12);
  EXPECT_NEAR(s->max_s, 0.030, 1e-12);
  EXPECT_NEAR(s->std_s, std::sqrt(200.0 / 3.0) * 1e-3, 1e-12);
}

TEST(TopicStats, OnlyTheLastSamplesOfTheWindowCount) {
  // 1 s apart, then 10 ms apart: a window of 3 sees only the fast part.
  ArrivalWindow w = window_of(3, {0, 1000 * kMs, 2000 * kMs, 2010 * kMs, 2020 * kMs});
  EXPECT_EQ(w.arrivals().size(), 3u);
  EXPECT_EQ(w.total(), 5u);
  const auto s = period_stats(w);
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->rate_hz, 100.0, 1e-9);
  EXPECT_NEAR(s->max_s, 0.010, 1e-12);
}

TEST(TopicStats, ALateHandedSampleIsPutInTimeOrder) {
  // Two writers' samples stamped by two receive threads: 20 ms handed over after 30 ms.
  const ArrivalWindow w = window_of(10, {0, 10 * kMs, 30 * kMs, 20 * kMs});
  ASSERT_EQ(w.arrivals().size(), 4u);
  EXPECT_EQ(w.arrivals()[2].time_ns, 20 * kMs);
  const auto s = period_stats(w);
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->min_s, 0.010, 1e-12);  // not -0.010
  EXPECT_NEAR(s->std_s, 0.0, 1e-12);
}

TEST(TopicStats, SizesGiveBandwidthMeanAndExtremes) {
  // 100, 200, 300 B at 0, 0.5 s, 1 s: after the first, 500 B in 1 s.
  ArrivalWindow w(10);
  w.add(Arrival{0, 100});
  w.add(Arrival{500 * kMs, 200});
  w.add(Arrival{1000 * kMs, 300});
  const auto s = size_stats(w);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->messages, 3u);
  EXPECT_NEAR(s->bytes_per_s, 500.0, 1e-9);
  EXPECT_NEAR(s->mean_bytes, 200.0, 1e-12);
  EXPECT_EQ(s->min_bytes, 100u);
  EXPECT_EQ(s->max_bytes, 300u);
}

TEST(TopicStats, SteadyStreamBandwidthIsSizeTimesRate) {
  // 76-byte samples at 100 Hz (plant/state of one robot): 7600 B/s.
  std::vector<std::int64_t> t;
  for (int i = 0; i < 100; ++i) t.push_back(i * 10 * kMs);
  const auto s = size_stats(window_of(100, t, 76));
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->bytes_per_s, 7600.0, 1e-6);
  EXPECT_EQ(s->min_bytes, 76u);
  EXPECT_EQ(s->max_bytes, 76u);
}

}  // namespace
}  // namespace robodds
