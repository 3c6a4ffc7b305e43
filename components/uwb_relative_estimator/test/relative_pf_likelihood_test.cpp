#include "components/uwb_relative_estimator/relative_pf_likelihood.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/angle.hpp"
#include "common/random.hpp"
#include "components/uwb_relative_estimator/relative_pose.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

Eigen::MatrixXd ranges_for(const model::Pose2& pose, const model::UwbArray& own, const model::UwbArray& other) {
  Eigen::MatrixXd ranges(static_cast<Eigen::Index>(own.nodes_m.size()), static_cast<Eigen::Index>(other.nodes_m.size()));
  for (std::size_t k = 0; k < own.nodes_m.size(); ++k) {
    for (std::size_t l = 0; l < other.nodes_m.size(); ++l) {
      ranges(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l)) = predicted_range(pose, own.nodes_m[k], other.nodes_m[l]);
    }
  }
  return ranges;
}

std::string error_of(const Eigen::MatrixXd& ranges, const model::UwbArray& own, const model::UwbArray& other) {
  try {
    require_valid_ranges("test", own, other, ranges);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(PoseLogLikelihood, LambdasAreStandardDeviations) {
  // One lambda off in position or heading costs 1/2 in log-likelihood (eq. 5-6 read with
  // lambda^2 in the denominators); reading them as variances would give 0.15 and 0.05.
  const model::Pose2 z{2.0, 1.0, 0.5};
  EXPECT_DOUBLE_EQ(pose_log_likelihood(z, z, 0.3, 0.1), 0.0);
  EXPECT_NEAR(pose_log_likelihood({2.3, 1.0, 0.5}, z, 0.3, 0.1), -0.5, 1e-12);
  EXPECT_NEAR(pose_log_likelihood({2.0, 0.7, 0.5}, z, 0.3, 0.1), -0.5, 1e-12);
  EXPECT_NEAR(pose_log_likelihood({2.0, 1.0, 0.6}, z, 0.3, 0.1), -0.5, 1e-12);
  // The position term is the squared distance: 0.3 m along a diagonal costs the same.
  const double d = 0.3 / std::sqrt(2.0);
  EXPECT_NEAR(pose_log_likelihood({2.0 + d, 1.0 + d, 0.5}, z, 0.3, 0.1), -0.5, 1e-12);
}

TEST(PoseLogLikelihood, HeadingDifferenceIsWrappedAcrossPi) {
  // 0.1 rad apart across the +-pi seam, not 2 pi - 0.1.
  EXPECT_NEAR(pose_log_likelihood({0.0, 0.0, -kPi + 0.05}, {0.0, 0.0, kPi - 0.05}, 0.3, 0.1), -0.5, 1e-9);
}

TEST(RangeLogLikelihood, PrefersTheTruePoseOverA90DegreeRotatedOne) {
  // The baseline [22] must see the heading through the 16 node-to-node ranges: j turned by 90 deg
  // on the spot keeps its centre (and so the mean range) but moves every node.
  const model::UwbArray array = model::square_array(0.5);
  RandomEngine engine(derive_seed(3, "range_likelihood"));
  for (const double bearing : {0.3, 2.0, -2.5}) {
    const model::Pose2 truth{4.0 * std::cos(bearing), 4.0 * std::sin(bearing), 0.7 - bearing};
    Eigen::MatrixXd ranges = ranges_for(truth, array, array);
    for (Eigen::Index k = 0; k < ranges.size(); ++k) {
      ranges.data()[k] += 0.05 * standard_normal(engine);
    }
    const model::Pose2 turned{truth.x, truth.y, wrap_angle(truth.theta + kPi / 2.0)};
    const double at_truth = range_log_likelihood(truth, array, array, ranges, 0.3);
    const double at_turned = range_log_likelihood(turned, array, array, ranges, 0.3);
    EXPECT_GT(at_truth, -1.0) << "bearing " << bearing;  // 16 residuals of 0.05 m at std 0.3: ~ -0.2
    EXPECT_LT(at_turned, at_truth - 5.0) << "bearing " << bearing;
  }
}

TEST(RangeLogLikelihood, IsTheSumOfSquaredResidualsOverTwoSigmaSquared) {
  const model::UwbArray array = model::square_array(0.5);
  const model::Pose2 truth{3.0, -1.0, 0.4};
  const Eigen::MatrixXd ranges = ranges_for(truth, array, array);
  EXPECT_NEAR(range_log_likelihood(truth, array, array, ranges, 0.3), 0.0, 1e-12);
  // Every one of the 16 ranges 0.3 m longer: 16 x (-1/2).
  EXPECT_NEAR(range_log_likelihood(truth, array, array, (ranges.array() + 0.3).matrix(), 0.3), -8.0, 1e-9);
  // Far off: a large negative number, not an underflowed 0 of a product of densities.
  const double far = range_log_likelihood({8.0, -1.0, 0.4}, array, array, ranges, 0.3);
  EXPECT_TRUE(std::isfinite(far));
  EXPECT_LT(far, -1000.0);
}

TEST(RequireValidRanges, NamesTheBadRangeOrTheSizeMismatch) {
  const model::UwbArray array = model::square_array(0.5);
  Eigen::MatrixXd ranges = ranges_for({3.0, 0.0, 0.0}, array, array);
  EXPECT_EQ(error_of(ranges, array, array), "");
  ranges(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_of(ranges, array, array), "test: range (1, 2): must be >= 0 and finite (got nan)");
  ranges(1, 2) = -0.5;
  EXPECT_EQ(error_of(ranges, array, array), "test: range (1, 2): must be >= 0 and finite (got -0.5)");
  EXPECT_EQ(error_of(Eigen::MatrixXd::Ones(4, 3), array, array), "test: ranges are 4 x 3, the arrays need 4 x 4");
  EXPECT_EQ(error_of(Eigen::MatrixXd::Ones(4, 0), array, model::UwbArray{}), "test: both arrays need at least one node (got 4 and 0)");
}

TEST(RequireFinitePose, NamesTheCallerAndThePose) {
  try {
    require_finite_pose("f", {1.0, std::numeric_limits<double>::quiet_NaN(), 0.0});
    FAIL() << "accepted a NaN";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "f: measured pose is not finite (got x=1, y=nan, theta=0)");
  }
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator
