#include "components/pf_estimator/regularization.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>

namespace robodds::pf_estimator {

double optimal_kernel_bandwidth(Eigen::Index num_particles) {
  constexpr double kStateDimension = 3.0;
  const double m = static_cast<double>(num_particles);
  return std::pow(4.0 / (m * (kStateDimension + 2.0)), 1.0 / (kStateDimension + 4.0));
}

Eigen::Matrix3d kernel_square_root(const Eigen::Matrix3d& covariance, double bandwidth) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  const Eigen::Vector3d std_devs = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  return bandwidth * eigen.eigenvectors() * std_devs.asDiagonal();
}

double kernel_shrinkage(double bandwidth) {
  return bandwidth >= 1.0 ? 0.0 : std::sqrt(1.0 - bandwidth * bandwidth);
}

}  // namespace robodds::pf_estimator
