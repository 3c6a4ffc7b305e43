#include "sim/evaluator/track.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace robodds::evaluator {
namespace {

using Track = std::vector<PoseSample>;

/// Feeds all of truth, then all of the estimates, as a run that delivers truth first would.
ErrorStats matched(const Track& truth, const Track& estimates, std::uint64_t from_step, MatchedError::ErrorFn error) {
  TruthWindow window;
  MatchedError m(error, from_step);
  for (const PoseSample& t : truth) {
    window.add(t);
  }
  for (const PoseSample& e : estimates) {
    m.add(e);
    m.match(window);
  }
  return m.stats();
}

TEST(TrackSummary, PathLengthSumsSegmentsAndKeepsTheLastSample) {
  TrackSummary t;
  EXPECT_TRUE(t.empty());
  EXPECT_DOUBLE_EQ(t.path_length(), 0.0);
  for (const PoseSample& s : Track{{0, 0, 0, 0}, {1, 3, 4, 0}, {2, 3, 5, 0.5}}) {
    t.add(s);
  }
  EXPECT_DOUBLE_EQ(t.path_length(), 6.0);
  EXPECT_EQ(t.count(), 3u);
  EXPECT_EQ(t.last().step, 2u);
  EXPECT_DOUBLE_EQ(t.last().theta, 0.5);
}

TEST(MatchedError, PositionErrorMatchesEqualStepsOnly) {
  const Track truth{{0, 0, 0, 0}, {1, 1, 0, 0}, {2, 2, 0, 0}, {3, 3, 0, 0}};
  const Track est{{1, 1, 3, 0}, {3, 3, 0, 0}, {4, 9, 9, 0}};  // step 4 has no truth
  const ErrorStats s = matched(truth, est, 0, position_distance);
  EXPECT_EQ(s.count, 2u);
  EXPECT_NEAR(s.rmse, std::sqrt(9.0 / 2.0), 1e-12);
  EXPECT_DOUBLE_EQ(s.max_abs, 3.0);
  EXPECT_EQ(matched(truth, est, 2, position_distance).count, 1u);
}

TEST(MatchedError, HeadingErrorWraps) {
  EXPECT_NEAR(matched({{0, 0, 0, 3.1}}, {{0, 0, 0, -3.1}}, 0, heading_difference).rmse, 2.0 * M_PI - 6.2, 1e-12);
}

TEST(MatchedError, AnEstimateWaitsForTheTruthOfItsStep) {
  TruthWindow window;
  MatchedError m(position_distance, 0);
  window.add({0, 0, 0, 0});
  m.add({1, 0, 2, 0});  // before the truth of step 1
  m.add({2, 0, 1, 0});
  m.match(window);
  EXPECT_EQ(m.waiting(), 2u);
  EXPECT_EQ(m.stats().count, 0u);
  window.add({1, 0, 0, 0});
  m.match(window);
  EXPECT_EQ(m.waiting(), 1u) << "step 2 still waits";
  window.add({3, 0, 0, 0});  // step 2 never comes: truth has passed it
  m.match(window);
  EXPECT_EQ(m.waiting(), 0u);
  EXPECT_EQ(m.stats().count, 1u);
  EXPECT_DOUBLE_EQ(m.stats().rmse, 2.0);
}

TEST(MatchedError, AnEstimateOlderThanOneAlreadyMatchedDoesNotCount) {
  const Track truth{{0, 0, 0, 0}, {1, 0, 0, 0}, {2, 0, 0, 0}};
  const ErrorStats s = matched(truth, {{2, 1, 0, 0}, {1, 5, 0, 0}, {2, 1, 0, 0}}, 0, position_distance);
  EXPECT_EQ(s.count, 2u) << "step 1 after step 2 is out of order; a repeated step counts again";
  EXPECT_DOUBLE_EQ(s.max_abs, 1.0);
}

TEST(TruthWindow, KeepsWhatIsNeededAndAtMostItsCapacity) {
  TruthWindow window(3);
  EXPECT_FALSE(window.reached(0));
  for (std::uint64_t step = 0; step < 5; ++step) {
    window.add({step, static_cast<double>(step), 0, 0});
  }
  EXPECT_EQ(window.size(), 3u);
  EXPECT_EQ(window.at(1), nullptr) << "beyond the capacity";
  ASSERT_NE(window.at(2), nullptr);
  EXPECT_DOUBLE_EQ(window.at(2)->x, 2.0);
  EXPECT_TRUE(window.reached(4));
  EXPECT_FALSE(window.reached(5));
  window.drop_before(4);
  EXPECT_EQ(window.size(), 1u);
  EXPECT_TRUE(window.reached(4)) << "dropping samples does not forget how far truth went";
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
