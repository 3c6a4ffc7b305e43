#include "components/range_rate_observer/running_abs_median.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <vector>

#include "common/random.hpp"

namespace robodds::range_rate_observer {
namespace {

TEST(RunningAbsMedian, MedianOfTheAbsoluteValuesHeld) {
  RunningAbsMedian m(5);
  EXPECT_EQ(m.median_abs(), 0.0);
  EXPECT_EQ(m.count(), 0u);
  m.add(-3.0);
  EXPECT_EQ(m.median_abs(), 3.0);
  m.add(1.0);
  EXPECT_EQ(m.median_abs(), 1.0);  // even count: the lower middle one
  m.add(-2.0);
  EXPECT_EQ(m.median_abs(), 2.0);
  EXPECT_EQ(m.count(), 3u);
}

TEST(RunningAbsMedian, ForgetsTheOldestOnceTheWindowIsFull) {
  RunningAbsMedian m(3);
  for (const double x : {100.0, 100.0, 100.0, 1.0, -1.0}) {
    m.add(x);
  }
  // Held: 100, 1, 1 (the first two 100s left).
  EXPECT_EQ(m.count(), 3u);
  EXPECT_EQ(m.median_abs(), 1.0);
  m.add(1.0);
  EXPECT_EQ(m.median_abs(), 1.0);
  m.add(5.0);
  m.add(5.0);
  EXPECT_EQ(m.median_abs(), 5.0);
}

TEST(RunningAbsMedian, EstimatesAGaussianSigmaAndIgnoresAMinorityOfJumps) {
  // 128 values (the observer's window), sigma 2.83 (the step spread at 2 m of range noise):
  // within 25 % (2.5 sigma of the median's ~10 %) on 20 seeds, with or without 10 % of steps
  // 500 m wide; a mean |x| or an RMS would be ~100 m or more with those.
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    RandomEngine engine(seed);
    RunningAbsMedian clean(128);
    RunningAbsMedian jumpy(128);
    for (int k = 0; k < 1000; ++k) {
      const double x = 2.83 * standard_normal(engine);
      clean.add(x);
      jumpy.add(k % 10 == 0 ? 500.0 : x);
    }
    EXPECT_NEAR(clean.sigma(), 2.83, 0.25 * 2.83) << seed;
    EXPECT_NEAR(jumpy.sigma(), 2.83, 0.35 * 2.83) << seed;  // the median of the other 90 %: ~1.13x wider
    EXPECT_LT(jumpy.sigma(), 5.0) << seed;
  }
}

TEST(RunningAbsMedian, AgreesWithSortingTheLastValues) {
  // The in-place replacement of the oldest value against a sort of the last `window` |x|, with
  // ties (rounded values) and both directions of the move.
  for (const std::size_t window : {1u, 2u, 7u, 64u}) {
    RandomEngine engine(window);
    RunningAbsMedian m(window);
    std::vector<double> all;
    for (int k = 0; k < 2000; ++k) {
      const double x = std::round(4.0 * standard_normal(engine)) / 2.0;
      m.add(x);
      all.push_back(std::abs(x));
      std::vector<double> last(all.end() - static_cast<std::ptrdiff_t>(std::min(all.size(), window)), all.end());
      std::sort(last.begin(), last.end());
      ASSERT_EQ(m.median_abs(), last[(last.size() - 1) / 2]) << "window " << window << ", value " << k;
    }
  }
}

TEST(RunningAbsMedian, BadInput) {
  EXPECT_THROW(RunningAbsMedian(0), std::invalid_argument);
  RunningAbsMedian m(4);
  m.add(1.0);
  EXPECT_THROW(m.add(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(m.add(std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_EQ(m.count(), 1u);
  EXPECT_EQ(m.median_abs(), 1.0);
}

}  // namespace
}  // namespace robodds::range_rate_observer
