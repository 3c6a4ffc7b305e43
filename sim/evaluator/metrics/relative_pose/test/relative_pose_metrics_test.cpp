#include "sim/evaluator/metrics/relative_pose/relative_pose_metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angle.hpp"

namespace robodds::evaluator {
namespace {

constexpr double kDeg = 180.0 / kPi;

// i at (1, 2) facing +y, j at (1, 5) facing -x: j is 3 m straight ahead of i, turned +90 deg.
const model::Pose2 kWorldI{1.0, 2.0, kPi / 2};
const model::Pose2 kWorldJ{1.0, 5.0, kPi};

TEST(RelativePoseError, IsTakenInTheBodyFrameOfRobotI) {
  const RelativePoseError e = relative_pose_error(kWorldI, kWorldJ, {3.3, 0.4, kPi / 2 + 0.1});
  EXPECT_NEAR(e.position_m, 0.5, 1e-12) << "(0.3, 0.4) off the truth (3, 0)";
  EXPECT_NEAR(e.heading_rad, 0.1, 1e-12);
}

TEST(RelativePoseError, HeadingErrorIsWrappedAcrossPlusMinusPi) {
  // Truth 3.1 rad, estimate -3.1 rad: 0.083 rad apart across +-pi, not 6.2.
  const RelativePoseError e = relative_pose_error({0.0, 0.0, 0.0}, {2.0, 0.0, 3.1}, {2.0, 0.0, -3.1});
  EXPECT_NEAR(e.position_m, 0.0, 1e-12);
  EXPECT_NEAR(e.heading_rad, 2.0 * kPi - 6.2, 1e-12);
}

TEST(RunningStats, GivesTheMeanAndThePopulationStd) {
  RunningStats s;
  for (double v : {2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0}) {
    s.add(v);
  }
  EXPECT_EQ(s.count(), 8u);
  EXPECT_DOUBLE_EQ(s.mean(), 5.0);
  EXPECT_DOUBLE_EQ(s.stddev(), 2.0) << "population std (divided by n; the sample std would be 2.138)";
}

TEST(RelativePoseMetrics, PoolsThePairsOfAStageFromMetricsAfterOn) {
  RelativePoseMetrics m(1.0);
  m.add_valid("pf", 0.99, kWorldI, kWorldJ, {30.0, 0.0, 0.0});  // before metrics_after_s: ignored
  m.add_invalid("pf", 0.5);                                      // likewise
  m.add_valid("pf", 1.0, kWorldI, kWorldJ, {3.3, 0.4, kPi / 2 + 0.1});          // pair (i, j): 0.5 m, 0.1 rad
  m.add_valid("pf", 1.1, {0.0, 0.0, 0.0}, {2.0, 0.0, 3.1}, {2.0, 0.0, -3.1});   // another pair: 0 m, 0.083 rad
  m.add_invalid("pf", 1.2);
  m.add_valid("uwb", 1.0, kWorldI, kWorldJ, {3.0, 0.0, kPi / 2 - 0.2});  // -0.2 rad: |.| counts
  m.expect_stage("window");

  const auto stages = m.stages();
  ASSERT_EQ(stages.size(), 3u);
  const RelativeStageStats& pf = stages.at("pf");
  EXPECT_EQ(pf.epochs, 2u);
  EXPECT_EQ(pf.invalid_epochs, 1u);
  EXPECT_NEAR(pf.position_error_m_mean, 0.25, 1e-12);
  EXPECT_NEAR(pf.position_error_m_std, 0.25, 1e-12);
  const double wrapped = 2.0 * kPi - 6.2;
  EXPECT_NEAR(pf.heading_error_deg_mean, (0.1 + wrapped) / 2 * kDeg, 1e-9);
  EXPECT_NEAR(pf.heading_error_deg_std, (0.1 - wrapped) / 2 * kDeg, 1e-9);

  const RelativeStageStats& uwb = stages.at("uwb");
  EXPECT_EQ(uwb.epochs, 1u);
  EXPECT_NEAR(uwb.position_error_m_mean, 0.0, 1e-12);
  EXPECT_NEAR(uwb.heading_error_deg_mean, 0.2 * kDeg, 1e-9) << "the mean of |error|, not of the signed error";
  EXPECT_EQ(uwb.heading_error_deg_std, 0.0);

  const RelativeStageStats& window = stages.at("window");
  EXPECT_EQ(window.epochs, 0u);
  EXPECT_EQ(window.invalid_epochs, 0u);
}

}  // namespace
}  // namespace robodds::evaluator
