#include "components/pf_estimator/regularization.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace robodds::pf_estimator {
namespace {

TEST(OptimalKernelBandwidth, MatchesTheGaussianKernelFormulaForThreeStates) {
  EXPECT_NEAR(optimal_kernel_bandwidth(1000), std::pow(4.0 / 5000.0, 1.0 / 7.0), 1e-15);
  EXPECT_NEAR(optimal_kernel_bandwidth(1000), 0.3611, 1e-4);
  // More particles, narrower kernel.
  EXPECT_LT(optimal_kernel_bandwidth(5000), optimal_kernel_bandwidth(100));
}

TEST(KernelSquareRoot, ReproducesTheScaledCovariance) {
  Eigen::Matrix3d a;
  a << 1.0, 0.2, -0.3,  //
      0.0, 0.5, 0.1,    //
      0.4, 0.0, 0.05;
  const Eigen::Matrix3d covariance = a * a.transpose();
  const Eigen::Matrix3d root = kernel_square_root(covariance, 0.3);
  EXPECT_TRUE((root * root.transpose()).isApprox(0.09 * covariance, 1e-12));
}

TEST(KernelSquareRoot, DegenerateCovarianceGivesNoJitterAlongTheFlatDirections) {
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  covariance(2, 2) = 0.04;  // only heading spread
  const Eigen::Matrix3d root = kernel_square_root(covariance, 1.0);
  ASSERT_TRUE(root.allFinite());
  EXPECT_NEAR(root.row(0).norm(), 0.0, 1e-15);
  EXPECT_NEAR(root.row(1).norm(), 0.0, 1e-15);
  EXPECT_NEAR(root.row(2).norm(), 0.2, 1e-12);
  // Slightly negative eigenvalues from rounding are clamped, not turned into NaN.
  covariance(0, 0) = -1e-18;
  EXPECT_TRUE(kernel_square_root(covariance, 1.0).allFinite());
}

TEST(KernelShrinkage, ShrinkagePlusJitterKeepsTheVariance) {
  for (double h : {0.0, 0.18, 0.5, 0.9}) {
    const double a = kernel_shrinkage(h);
    EXPECT_NEAR(a * a + h * h, 1.0, 1e-15) << h;
  }
  EXPECT_EQ(kernel_shrinkage(1.0), 0.0);
  EXPECT_EQ(kernel_shrinkage(2.0), 0.0);
}

}  // namespace
}  // namespace robodds::pf_estimator
