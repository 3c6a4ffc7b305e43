#include "sim/evaluator/metrics/waypoints/leg_deviation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

namespace robodds::evaluator {
namespace {

TEST(LegDeviation, CountsTheCrossTrackErrorAfterTheFirstTenMetresOfEachLeg) {
  LegDeviation legs;
  legs.set_mission({{{100.0, 0.0}}, {{100.0, 100.0}}});
  legs.add_truth(0, 0.0, 0.0);  // the first leg starts here
  legs.add_status(0, 0, false);
  legs.add_truth(1, 5.0, 3.0);    // 5 m along: the turn onto the leg, not counted
  legs.add_truth(2, 50.0, 2.0);   // +2 m (left of an eastward leg)
  legs.add_truth(3, 60.0, -1.0);  // -1 m
  legs.add_status(4, 1, false);   // switched: the leg (100, 0) -> (100, 100), heading north
  legs.add_truth(4, 103.0, 5.0);  // 5 m along: not counted
  legs.add_truth(5, 98.0, 50.0);  // 2 m left of a northward leg
  EXPECT_EQ(legs.figures()->samples, 2u);  // step 5 waits for a status that covers it
  legs.add_status(6, 1, false);
  const auto f = legs.figures();
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->samples, 3u);
  EXPECT_NEAR(f->cross_track_rms_m, std::sqrt((4.0 + 1.0 + 4.0) / 3.0), 1e-12);
  EXPECT_DOUBLE_EQ(f->cross_track_max_m, 2.0);
}

TEST(LegDeviation, TruthAheadOfTheStatusWaitsForItsLeg) {
  // The plant runs at 100 Hz, the controller slower: truth of steps after the newest status
  // must take the leg the next status names, when that status switched.
  LegDeviation legs;
  legs.set_mission({{{100.0, 0.0}}, {{100.0, 100.0}}});
  legs.add_truth(0, 0.0, 0.0);
  legs.add_status(0, 0, false);
  legs.add_truth(10, 100.5, 40.0);  // already on the second leg, its status not yet here
  legs.add_status(10, 1, false);
  const auto f = legs.figures();
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->samples, 1u);
  EXPECT_NEAR(f->cross_track_max_m, 0.5, 1e-12);  // against the second leg (against the first: 40 m)
}

TEST(LegDeviation, NothingCountsOnceDoneNorBeyondTheWaypoint) {
  LegDeviation legs;
  legs.set_mission({{{100.0, 0.0}}});
  legs.add_truth(0, 0.0, 0.0);
  legs.add_status(0, 0, false);
  legs.add_truth(1, 105.0, 7.0);  // past the way-point: not on the leg any more
  legs.add_status(2, 0, true);
  legs.add_truth(2, 50.0, 30.0);  // after done
  legs.add_truth(3, 50.0, 30.0);
  EXPECT_FALSE(legs.figures().has_value());
}

TEST(LegDeviation, TruthWaitingForAStatusIsBounded) {
  // A controller whose status stops: the truth that waits for it must not grow with the run.
  LegDeviation legs;
  legs.set_mission({{{1000.0, 0.0}}});
  legs.add_truth(0, 0.0, 0.0);
  legs.add_status(0, 0, false);
  for (std::uint64_t k = 1; k <= 3 * LegDeviation::kMaxPending; ++k) {
    legs.add_truth(k, 0.01 * static_cast<double>(k), 1.0);
  }
  legs.add_status(3 * LegDeviation::kMaxPending, 0, false);  // counts what was kept
  ASSERT_TRUE(legs.figures().has_value());
  EXPECT_EQ(legs.figures()->samples, LegDeviation::kMaxPending);  // the newest kept (all beyond 10 m along); 11,288 without the bound
}

TEST(LegDeviation, NoStatusNoFigure) {
  LegDeviation legs;
  legs.set_mission({{{100.0, 0.0}}});
  legs.add_truth(0, 0.0, 0.0);
  legs.add_truth(1, 50.0, 1.0);
  EXPECT_FALSE(legs.figures().has_value());
}

}  // namespace
}  // namespace robodds::evaluator
