// Errors judged against the covariance an estimate reports (sim/evaluator/consistency.hpp).
#include "sim/evaluator/consistency.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace robodds::evaluator {
namespace {

EstimateError error(std::uint64_t step, bool valid, double ex, double ey, double etheta, double var_xy, double var_theta) {
  EstimateError e;
  e.step = step;
  e.valid = valid;
  e.ex = ex;
  e.ey = ey;
  e.etheta = etheta;
  e.cov = {var_xy, 0, 0, 0, var_xy, 0, 0, 0, var_theta};
  return e;
}

TEST(ConsistencyTracker, OutsideTheReportedThreeSigmaIsOverconfident) {
  // sigma 1 m: the 3-sigma ellipse has radius sqrt(11.829) = 3.44 m.
  EXPECT_FALSE(overconfident(error(0, true, 3.4, 0.0, 0.0, 1.0, 0.01)));
  EXPECT_TRUE(overconfident(error(0, true, 3.5, 0.0, 0.0, 1.0, 0.01)));
  EXPECT_TRUE(overconfident(error(0, true, 2.5, 2.5, 0.0, 1.0, 0.01))) << "3.54 m diagonal";
  EXPECT_FALSE(overconfident(error(0, true, 0.0, 0.0, 0.29, 1.0, 0.01))) << "heading sigma 0.1 rad: 3 sigma 0.3";
  EXPECT_TRUE(overconfident(error(0, true, 0.0, 0.0, -0.31, 1.0, 0.01)));
  EXPECT_FALSE(overconfident(error(0, false, 50.0, 0.0, 3.0, 1.0, 0.01))) << "an invalid estimate claims nothing";
  EXPECT_TRUE(overconfident(error(0, true, 0.01, 0.0, 0.0, 0.0, 0.01))) << "zero covariance, nonzero error";
  EXPECT_FALSE(overconfident(error(0, true, 0.0, 0.0, 0.0, 0.0, 0.0))) << "zero covariance, no error";
  // A correlated covariance: the ellipse is long along x = y.
  EstimateError along = error(0, true, 3.0, 3.0, 0.0, 1.0, 0.01);
  along.cov[1] = along.cov[3] = 0.9;
  EXPECT_FALSE(overconfident(along)) << "d2 = 18 / 1.9 = 9.5 along the long axis";
  EstimateError across = error(0, true, 3.0, -3.0, 0.0, 1.0, 0.01);
  across.cov[1] = across.cov[3] = 0.9;
  EXPECT_TRUE(overconfident(across)) << "d2 = 18 / 0.1 = 180 across it";
}

TEST(ConsistencyTracker, AConsistentEstimatorIsRarelyOverconfident) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 1.0);
  ConsistencyTracker honest(0.01), overconfident_by_3(0.01);
  for (std::uint64_t k = 0; k < 100000; ++k) {
    const double ex = 2.0 * n(rng), ey = 2.0 * n(rng), et = 0.05 * n(rng);
    honest.add(error(k, true, ex, ey, et, 4.0, 0.0025));
    overconfident_by_3.add(error(k, true, ex, ey, et, 4.0 / 9.0, 0.0025 / 9.0));
  }
  // Position 0.27 % + heading 0.27 %, nearly independent: ~0.54 %.
  EXPECT_NEAR(honest.stats().overconfident_fraction, 0.0054, 0.0015);
  EXPECT_GT(overconfident_by_3.stats().overconfident_fraction, 0.5) << "sigma reported 3x too small";
}

TEST(ConsistencyTracker, WorstErrorsWhileValidAndTheLongestOverconfidentRun) {
  ConsistencyTracker t(0.1);
  t.add(error(0, false, 40.0, 0.0, 3.0, 1.0, 0.01));  // invalid: not counted as worst
  t.add(error(1, true, 5.0, 0.0, 0.0, 1.0, 0.01));    // over-confident
  t.add(error(2, true, 0.0, 6.0, 0.0, 1.0, 0.01));    // over-confident
  t.add(error(3, true, 0.0, 0.0, 0.2, 1.0, 0.01));    // fine
  t.add(error(4, true, 4.0, 0.0, 0.0, 1.0, 0.01));    // over-confident, a run of one
  const ConsistencyStats s = t.stats();
  EXPECT_EQ(s.samples, 5u);
  EXPECT_EQ(s.valid_samples, 4u);
  EXPECT_EQ(s.overconfident, 3u);
  EXPECT_DOUBLE_EQ(s.overconfident_fraction, 0.75);
  EXPECT_DOUBLE_EQ(s.worst_position_error_valid_m, 6.0);
  EXPECT_DOUBLE_EQ(s.worst_heading_error_valid_rad, 0.2);
  EXPECT_NEAR(s.longest_overconfident_s, 0.2, 1e-12) << "steps 1 and 2";
  const ConsistencyStats both = pooled(s, ConsistencyTracker(0.1).stats());
  EXPECT_EQ(both.valid_samples, 4u);
  EXPECT_DOUBLE_EQ(both.overconfident_fraction, 0.75);
}

TEST(ConsistencyTracker, ScalarEstimatesAreJudgedAgainstThreeReportedStds) {
  EXPECT_FALSE(overconfident_scalar(true, 0.29, 0.01));
  EXPECT_TRUE(overconfident_scalar(true, -0.31, 0.01));
  EXPECT_FALSE(overconfident_scalar(false, 5.0, 0.01));
  EXPECT_TRUE(overconfident_scalar(true, 0.001, 0.0)) << "a claim of no error that the error contradicts";
  EXPECT_FALSE(overconfident_scalar(true, 0.0, 0.0));
  ConsistencyTracker t(0.02);
  t.add_scalar(0, true, 0.1, 0.01);   // inside
  t.add_scalar(1, true, 0.5, 0.01);   // outside
  t.add_scalar(2, true, -0.4, 0.01);  // outside
  t.add_scalar(3, false, 9.0, 0.01);  // not valid: not judged, not the worst
  const ConsistencyStats s = t.stats();
  EXPECT_EQ(s.samples, 4u);
  EXPECT_EQ(s.valid_samples, 3u);
  EXPECT_EQ(s.overconfident, 2u);
  EXPECT_NEAR(s.longest_overconfident_s, 0.04, 1e-12);
  EXPECT_DOUBLE_EQ(s.worst_position_error_valid_m, 0.5);
  EXPECT_DOUBLE_EQ(s.worst_heading_error_valid_rad, 0.0);
}

}  // namespace
}  // namespace robodds::evaluator
