#include "components/pf_estimator/pose_estimate.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angle.hpp"

namespace robodds::pf_estimator {
namespace {

ParticleSet make_particles(std::initializer_list<double> x, std::initializer_list<double> y,
                           std::initializer_list<double> theta) {
  ParticleSet particles;
  particles.resize(static_cast<Eigen::Index>(x.size()));
  Eigen::Index i = 0;
  for (const double v : x) particles.x[i++] = v;
  i = 0;
  for (const double v : y) particles.y[i++] = v;
  i = 0;
  for (const double v : theta) particles.theta[i++] = v;
  return particles;
}

TEST(WeightedPoseEstimate, PositionIsTheWeightedMeanOfEquationSeven) {
  const ParticleSet particles = make_particles({0.0, 2.0, 4.0}, {1.0, 1.0, -2.0}, {0.1, 0.1, 0.1});
  Eigen::ArrayXd w(3);
  w << 0.5, 0.25, 0.25;
  const PoseEstimate estimate = weighted_pose_estimate(particles, w);
  EXPECT_NEAR(estimate.mean.x(), 1.5, 1e-15);
  EXPECT_NEAR(estimate.mean.y(), 0.25, 1e-15);
  EXPECT_NEAR(estimate.mean.z(), 0.1, 1e-15);
  // var x = 0.5*2.25 + 0.25*0.25 + 0.25*6.25; cov xy = 0.5*(-1.5)(0.75) + 0.25*0.5*0.75 + 0.25*2.5*(-2.25)
  EXPECT_NEAR(estimate.covariance(0, 0), 2.75, 1e-12);
  EXPECT_NEAR(estimate.covariance(0, 1), -1.875, 1e-12);
  EXPECT_NEAR(estimate.covariance(1, 0), -1.875, 1e-12);
  EXPECT_NEAR(estimate.covariance(1, 1), 0.5 * 0.5625 + 0.25 * 0.5625 + 0.25 * 5.0625, 1e-12);
  EXPECT_NEAR(estimate.covariance(2, 2), 0.0, 1e-15);
}

TEST(WeightedPoseEstimate, HeadingMeanAndSpreadAreCircularAcrossPlusMinusPi) {
  // An arithmetic mean of these two would point to 0, i.e. exactly backwards.
  const ParticleSet particles = make_particles({0.0, 0.0}, {0.0, 0.0}, {kPi - 0.1, -kPi + 0.1});
  Eigen::ArrayXd w(2);
  w << 0.5, 0.5;
  const PoseEstimate estimate = weighted_pose_estimate(particles, w);
  EXPECT_NEAR(std::abs(wrap_angle(estimate.mean.z() - kPi)), 0.0, 1e-12);
  EXPECT_NEAR(estimate.covariance(2, 2), 0.01, 1e-12);
}

TEST(WeightedPoseEstimate, CovarianceIsSymmetricWithHeadingCrossTerms) {
  const ParticleSet particles = make_particles({-1.0, 1.0}, {0.0, 0.0}, {-0.2, 0.2});
  Eigen::ArrayXd w(2);
  w << 0.5, 0.5;
  const PoseEstimate estimate = weighted_pose_estimate(particles, w);
  EXPECT_NEAR(estimate.covariance(0, 2), 0.2, 1e-12);
  EXPECT_EQ(estimate.covariance(0, 2), estimate.covariance(2, 0));
  EXPECT_NEAR(estimate.covariance(2, 2), 0.04, 1e-12);
}

TEST(IsValid, NeedsASmallPositionSpreadAndASmallHeadingSpread) {
  PoseEstimate e;
  e.covariance.diagonal() << 1.0, 1.0, 0.01;  // position std sqrt(2), heading std 0.1 rad
  EXPECT_TRUE(is_valid(e, 3.0, 0.2));
  EXPECT_FALSE(is_valid(e, 1.0, 0.2));   // position too uncertain
  EXPECT_FALSE(is_valid(e, 3.0, 0.05));  // heading too uncertain
  EXPECT_TRUE(is_valid(e, 3.0, 0.0));    // heading not checked
}

PoseEstimate with_stds(double position_std_m, double heading_std_rad) {
  PoseEstimate e;
  const double axis_var = position_std_m * position_std_m / 2.0;
  e.covariance.diagonal() << axis_var, axis_var, heading_std_rad * heading_std_rad;
  return e;
}

TEST(NextValidity, EntersBelowTheEnterLimitAndStaysUntilTheKeepLimit) {
  const ValidityLimits limits{3.0, 0.2, 0.35};
  EXPECT_FALSE(next_validity(with_stds(1.0, 0.25), limits, false));  // in the band, not yet valid
  EXPECT_TRUE(next_validity(with_stds(1.0, 0.19), limits, false));   // enters
  EXPECT_TRUE(next_validity(with_stds(1.0, 0.25), limits, true));    // in the band, stays
  EXPECT_TRUE(next_validity(with_stds(1.0, 0.349), limits, true));
  EXPECT_FALSE(next_validity(with_stds(1.0, 0.36), limits, true));   // beyond the keep limit
  EXPECT_FALSE(next_validity(with_stds(3.5, 0.1), limits, true));    // position: no band
}

TEST(NextValidity, NoBandWhenTheKeepLimitIsTheEnterLimitAndNoHeadingCheckAtZero) {
  EXPECT_FALSE(next_validity(with_stds(1.0, 0.25), {3.0, 0.2, 0.2}, true));
  EXPECT_TRUE(next_validity(with_stds(1.0, 3.0), {3.0, 0.0, 0.0}, false));
  EXPECT_TRUE(next_validity(with_stds(1.0, 3.0), {3.0, 0.0, 0.35}, true));
}

// Issue 27: once valid since the filter's last restart, an estimate whose heading spread passed the
// keep limit is valid again below the keep limit (a stopped robot cannot bring it below the enter
// limit); unconfirmed never; after a restart it must enter again.
TEST(ValidityTracker, ReentersBelowTheKeepLimitUntilTheFilterRestarts) {
  ValidityTracker validity({3.0, 0.2, 0.35});
  EXPECT_FALSE(validity.next(with_stds(1.0, 0.25), true, 0));   // in the band, never valid yet
  EXPECT_FALSE(validity.next(with_stds(1.0, 0.1), false, 0));   // not confirmed by the fixes
  EXPECT_TRUE(validity.next(with_stds(1.0, 0.19), true, 0));    // enters
  EXPECT_FALSE(validity.next(with_stds(1.0, 0.36), true, 0));   // beyond the keep limit
  EXPECT_TRUE(validity.next(with_stds(1.0, 0.3), true, 0)) << "established: the keep limit applies";
  EXPECT_FALSE(validity.next(with_stds(3.5, 0.1), true, 0));    // position: no band
  EXPECT_FALSE(validity.next(with_stds(1.0, 0.3), true, 1)) << "restarted: must enter again";
  EXPECT_TRUE(validity.next(with_stds(1.0, 0.19), true, 1));
  EXPECT_TRUE(validity.next(with_stds(1.0, 0.3), true, 1));
}

}  // namespace
}  // namespace robodds::pf_estimator
