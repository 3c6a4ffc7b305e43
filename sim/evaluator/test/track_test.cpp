#include "sim/evaluator/track.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace robodds::evaluator {
namespace {

TEST(Track, PathLengthSumsSegments) {
  const Track t{{0, 0, 0, 0}, {1, 3, 4, 0}, {2, 3, 5, 0}};
  EXPECT_DOUBLE_EQ(path_length(t), 6.0);
  EXPECT_DOUBLE_EQ(path_length({}), 0.0);
}

TEST(Track, PositionErrorMatchesEqualStepsOnly) {
  const Track truth{{0, 0, 0, 0}, {1, 1, 0, 0}, {2, 2, 0, 0}, {3, 3, 0, 0}};
  const Track est{{1, 1, 3, 0}, {3, 3, 0, 0}, {4, 9, 9, 0}};  // step 4 has no truth
  const ErrorStats s = position_error(truth, est, 0);
  EXPECT_EQ(s.count, 2u);
  EXPECT_NEAR(s.rmse, std::sqrt(9.0 / 2.0), 1e-12);
  EXPECT_DOUBLE_EQ(s.max_abs, 3.0);
  EXPECT_EQ(position_error(truth, est, 2).count, 1u);
}

TEST(Track, HeadingErrorWraps) {
  const Track truth{{0, 0, 0, 3.1}};
  const Track est{{0, 0, 0, -3.1}};
  EXPECT_NEAR(heading_error(truth, est, 0).rmse, 2.0 * M_PI - 6.2, 1e-12);
}

TEST(PooledRmse, WeightsEachRmseByItsSampleCount) {
  PooledRmse pool;
  EXPECT_TRUE(pool.empty());
  pool.add(ErrorStats{1.0, 1.0, 1});
  pool.add(ErrorStats{2.0, 2.0, 3});  // squares 1 x 1 + 4 x 3 = 13 over 4 samples
  EXPECT_FALSE(pool.empty());
  EXPECT_DOUBLE_EQ(pool.rmse(), std::sqrt(13.0 / 4.0));
  pool.add(ErrorStats{});  // no samples: changes nothing
  EXPECT_DOUBLE_EQ(pool.rmse(), std::sqrt(13.0 / 4.0));
}

}  // namespace
}  // namespace robodds::evaluator
