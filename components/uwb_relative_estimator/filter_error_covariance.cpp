#include "components/uwb_relative_estimator/filter_error_covariance.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/angle.hpp"
#include "components/uwb_relative_estimator/median.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace robodds::uwb_relative_estimator {

Eigen::Matrix3d update_gain(const Eigen::Matrix3d& prior, const Eigen::Matrix3d& measurement_covariance) {
  const Eigen::LLT<Eigen::Matrix3d> llt(prior + measurement_covariance);
  if (llt.info() != Eigen::Success) {
    return Eigen::Matrix3d::Zero();
  }
  // K = P S^-1 = (S^-1 P)^T for symmetric P and S.
  return llt.solve(prior).transpose();
}

FilterErrorCovariance::FilterErrorCovariance(const UncertaintyParams& params) : params_(params) { params_.validate(); }

void FilterErrorCovariance::start(const RangeErrorMap& error) {
  const double var_c = error.common_std_m * error.common_std_m;
  covariance_ = error.covariance();
  common_cross_ = var_c * error.common_map;
  independent_cross_ = error.independent_map * error.independent_variance_m2.asDiagonal();
  started_ = true;
}

void FilterErrorCovariance::start(const Eigen::Matrix3d& covariance) {
  covariance_ = covariance;
  common_cross_.setZero();
  independent_cross_.resize(3, 0);
  started_ = true;
}

void FilterErrorCovariance::predict(const model::Pose2& x, const model::Pose2& own_increment,
                                    const model::Pose2& other_increment, double dt_s, double xy_std_m,
                                    double theta_std_rad) {
  if (!started_) {
    return;
  }
  const Eigen::Matrix<double, 3, 9> jacobian = relative_motion_jacobian(x, own_increment, other_increment);
  const Eigen::Matrix3d f = jacobian.leftCols<3>();
  const Eigen::Vector3d increment_variance(xy_std_m * xy_std_m, xy_std_m * xy_std_m, theta_std_rad * theta_std_rad);
  const Eigen::Matrix3d noise = jacobian.middleCols<3>(3) * increment_variance.asDiagonal() * jacobian.middleCols<3>(3).transpose() +
                                jacobian.rightCols<3>() * increment_variance.asDiagonal() * jacobian.rightCols<3>().transpose();
  const Eigen::Matrix3d propagated = f * covariance_ * f.transpose() + noise;
  covariance_ = 0.5 * (propagated + propagated.transpose());
  common_cross_ = std::exp(-dt_s / params_.range_common_time_s) * (f * common_cross_);
  independent_cross_ = std::exp(-dt_s / params_.range_link_time_s) * (f * independent_cross_);
}

void FilterErrorCovariance::update(const Eigen::Matrix3d& gain, const RangeErrorMap& error) {
  if (!started_) {
    return;
  }
  if (independent_cross_.cols() != error.independent_map.cols()) {
    independent_cross_ = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, error.independent_map.cols());
  }
  const double var_c = error.common_std_m * error.common_std_m;
  const Eigen::Matrix3d keep = Eigen::Matrix3d::Identity() - gain;
  // Cov(eps, e) of the prior error with this measurement's error.
  const Eigen::Matrix3d cross = common_cross_ * error.common_map.transpose() +
                                independent_cross_ * error.independent_map.transpose();
  const Eigen::Matrix3d updated = keep * covariance_ * keep.transpose() + gain * error.covariance() * gain.transpose() +
                                  keep * cross * gain.transpose() + gain * cross.transpose() * keep.transpose();
  covariance_ = 0.5 * (updated + updated.transpose());
  common_cross_ = keep * common_cross_ + var_c * (gain * error.common_map);
  independent_cross_ = keep * independent_cross_ + gain * error.independent_map * error.independent_variance_m2.asDiagonal();
}

InnovationMonitor::InnovationMonitor(const UncertaintyParams& params) : params_(params) { params_.validate(); }

void InnovationMonitor::reset() {
  innovations_.clear();
  covariances_.clear();
}

void InnovationMonitor::add(const model::Pose2& estimate, const model::Pose2& fix, const Eigen::Matrix3d& fix_covariance) {
  const Eigen::Vector3d delta(fix.x - estimate.x, fix.y - estimate.y, wrap_angle(fix.theta - estimate.theta));
  if (!delta.allFinite() || !fix_covariance.allFinite()) {
    return;
  }
  innovations_.push_back(delta);
  covariances_.push_back(fix_covariance);
  while (innovations_.size() > static_cast<std::size_t>(params_.innovation_window_epochs)) {
    innovations_.pop_front();
    covariances_.pop_front();
  }
}

Eigen::Matrix3d InnovationMonitor::excess() const {
  const std::size_t needed = std::max<std::size_t>(3, static_cast<std::size_t>(params_.innovation_window_epochs) / 5);
  if (innovations_.size() < needed) {
    return Eigen::Matrix3d::Zero();
  }
  Eigen::Vector3d typical;
  Eigen::Matrix3d mean_s = Eigen::Matrix3d::Zero();
  for (int c = 0; c < 3; ++c) {
    std::vector<double> values;
    values.reserve(innovations_.size());
    for (const Eigen::Vector3d& d : innovations_) {
      values.push_back(d(c));
    }
    typical(c) = median(std::move(values));
  }
  for (const Eigen::Matrix3d& s : covariances_) {
    mean_s += s;
  }
  mean_s /= static_cast<double>(covariances_.size());
  const Eigen::Matrix3d unexplained = typical * typical.transpose() - mean_s;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(0.5 * (unexplained + unexplained.transpose()));
  if (eigen.info() != Eigen::Success) {
    return Eigen::Matrix3d::Zero();
  }
  const Eigen::Vector3d positive = eigen.eigenvalues().cwiseMax(0.0);
  return eigen.eigenvectors() * positive.asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace robodds::uwb_relative_estimator
