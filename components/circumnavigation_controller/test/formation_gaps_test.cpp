#include "components/circumnavigation_controller/formation_gaps.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <vector>

#include "common/angle.hpp"

namespace robodds::circumnavigation_controller {
namespace {

constexpr double kDeg = kPi / 180.0;
constexpr double kTol = 1e-12;

TEST(BearingFromTarget, IsTheDirectionFromTheTargetToThePoint) {
  EXPECT_NEAR(bearing_from_target(1200.0, 1000.0, 1000.0, 1000.0), 0.0, kTol);
  EXPECT_NEAR(bearing_from_target(1000.0, 1200.0, 1000.0, 1000.0), kPi / 2.0, kTol);
  EXPECT_NEAR(bearing_from_target(800.0, 1000.0, 1000.0, 1000.0), kPi, kTol);
  EXPECT_NEAR(bearing_from_target(1000.0, 800.0, 1000.0, 1000.0), -kPi / 2.0, kTol);
}

TEST(FormationGaps, ARobotAloneHasTheWholeCircleBothWays) {
  const Gaps g = formation_gaps({1, 0.3}, {});
  EXPECT_EQ(g.team_count, 1);
  EXPECT_DOUBLE_EQ(g.ahead_rad, 2.0 * kPi);
  EXPECT_DOUBLE_EQ(g.behind_rad, 2.0 * kPi);
  // Its own entry in the list is not a peer.
  const Gaps same = formation_gaps({1, 0.3}, {{1, 0.3}});
  EXPECT_EQ(same.team_count, 1);
  EXPECT_DOUBLE_EQ(same.ahead_rad, 2.0 * kPi);
}

TEST(FormationGaps, TwoRobotsAheadIsCounterClockwise) {
  const Gaps a = formation_gaps({1, 0.0}, {{2, 90.0 * kDeg}});
  EXPECT_EQ(a.team_count, 2);
  EXPECT_NEAR(a.ahead_rad, 90.0 * kDeg, kTol);
  EXPECT_NEAR(a.behind_rad, 270.0 * kDeg, kTol);
  const Gaps b = formation_gaps({2, 90.0 * kDeg}, {{1, 0.0}});
  EXPECT_NEAR(b.ahead_rad, 270.0 * kDeg, kTol);
  EXPECT_NEAR(b.behind_rad, 90.0 * kDeg, kTol);
}

TEST(FormationGaps, WrapsAroundPlusMinusPi) {
  // 170 deg to -170 deg is 20 deg counter-clockwise, not 340.
  const Gaps g = formation_gaps({1, 170.0 * kDeg}, {{2, -170.0 * kDeg}});
  EXPECT_NEAR(g.ahead_rad, 20.0 * kDeg, 1e-12);
  EXPECT_NEAR(g.behind_rad, 340.0 * kDeg, 1e-12);
  // Bearings outside (-pi, pi] are the same directions.
  const Gaps h = formation_gaps({1, 170.0 * kDeg + 4.0 * kPi}, {{2, -170.0 * kDeg - 2.0 * kPi}});
  EXPECT_NEAR(h.ahead_rad, 20.0 * kDeg, 1e-12);
}

TEST(FormationGaps, FourRobotsNearestOnEachSide) {
  // 0, 90, 180 (written -180) and 270 (written -90) deg, listed out of order.
  const std::vector<TeamBearing> team{{3, -kPi}, {1, 0.0}, {4, -kPi / 2.0}, {2, kPi / 2.0}};
  double sum_ahead = 0.0;
  for (const TeamBearing& own : team) {
    const Gaps g = formation_gaps(own, team);
    EXPECT_EQ(g.team_count, 4);
    EXPECT_NEAR(g.ahead_rad, kPi / 2.0, 1e-12) << own.robot_id;
    EXPECT_NEAR(g.behind_rad, kPi / 2.0, 1e-12) << own.robot_id;
    sum_ahead += g.ahead_rad;
  }
  EXPECT_NEAR(sum_ahead, 2.0 * kPi, 1e-12);
  // Uneven: robot 1 at 0 with the next at 30 deg and the previous at 200 deg.
  const Gaps u = formation_gaps({1, 0.0}, {{2, 30.0 * kDeg}, {3, 120.0 * kDeg}, {4, 200.0 * kDeg}});
  EXPECT_NEAR(u.ahead_rad, 30.0 * kDeg, 1e-12);
  EXPECT_NEAR(u.behind_rad, 160.0 * kDeg, 1e-12);
}

TEST(FormationGaps, IdenticalBearingsAreOrderedByIdSoTheyPartInsteadOfLocking) {
  // Robots 1 and 2 at the same bearing: 2 counts as ahead of 1 at gap 0. Robot 1 then sees a
  // small gap ahead (slows down), robot 2 a small gap behind (speeds up): they separate.
  const Gaps one = formation_gaps({1, 1.0}, {{2, 1.0}});
  EXPECT_DOUBLE_EQ(one.ahead_rad, 0.0);
  EXPECT_DOUBLE_EQ(one.behind_rad, 2.0 * kPi);
  const Gaps two = formation_gaps({2, 1.0}, {{1, 1.0}});
  EXPECT_DOUBLE_EQ(two.ahead_rad, 2.0 * kPi);
  EXPECT_DOUBLE_EQ(two.behind_rad, 0.0);
  // In a team of four with two identical bearings the forward gaps still add up to 2 pi.
  const std::vector<TeamBearing> team{{1, 1.0}, {2, 1.0}, {3, 2.0}, {4, -2.0}};
  double sum_ahead = 0.0;
  double sum_behind = 0.0;
  for (const TeamBearing& own : team) {
    const Gaps g = formation_gaps(own, team);
    sum_ahead += g.ahead_rad;
    sum_behind += g.behind_rad;
  }
  EXPECT_NEAR(sum_ahead, 2.0 * kPi, 1e-12);
  EXPECT_NEAR(sum_behind, 2.0 * kPi, 1e-12);
}

TEST(FormationGaps, NonFiniteBearingThrows) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(formation_gaps({1, nan}, {}), std::invalid_argument);
  EXPECT_THROW(formation_gaps({1, 0.0}, {{2, nan}}), std::invalid_argument);
}

}  // namespace
}  // namespace robodds::circumnavigation_controller
