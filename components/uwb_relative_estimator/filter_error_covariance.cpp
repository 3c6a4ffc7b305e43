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
  node_cross_ = error.node_bias_std_m * error.node_bias_std_m * error.node_map;
  started_ = true;
}

void FilterErrorCovariance::start(const Eigen::Matrix3d& covariance) {
  covariance_ = covariance;
  common_cross_.setZero();
  independent_cross_.resize(3, 0);
  node_cross_.resize(3, 0);
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
  // A node's bias lasts as long as what causes it (an antenna's delay, an obstacle in view):
  // counted as lasting as the common mode.
  node_cross_ = std::exp(-dt_s / params_.range_common_time_s) * (f * node_cross_);
}

void FilterErrorCovariance::update(const Eigen::Matrix3d& gain, const RangeErrorMap& error) {
  if (!started_) {
    return;
  }
  if (independent_cross_.cols() != error.independent_map.cols()) {
    independent_cross_ = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, error.independent_map.cols());
  }
  if (node_cross_.cols() != error.node_map.cols()) {
    node_cross_ = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, error.node_map.cols());
  }
  const double var_c = error.common_std_m * error.common_std_m;
  const double var_n = error.node_bias_std_m * error.node_bias_std_m;
  const Eigen::Matrix3d keep = Eigen::Matrix3d::Identity() - gain;
  // Cov(eps, e) of the prior error with this measurement's error.
  const Eigen::Matrix3d cross = common_cross_ * error.common_map.transpose() +
                                independent_cross_ * error.independent_map.transpose() +
                                node_cross_ * error.node_map.transpose();
  const Eigen::Matrix3d updated = keep * covariance_ * keep.transpose() + gain * error.covariance() * gain.transpose() +
                                  keep * cross * gain.transpose() + gain * cross.transpose() * keep.transpose();
  covariance_ = 0.5 * (updated + updated.transpose());
  common_cross_ = keep * common_cross_ + var_c * (gain * error.common_map);
  independent_cross_ = keep * independent_cross_ + gain * error.independent_map * error.independent_variance_m2.asDiagonal();
  node_cross_ = keep * node_cross_ + var_n * (gain * error.node_map);
}

InnovationMonitor::InnovationMonitor(const UncertaintyParams& params) : params_(params) { params_.validate(); }

void InnovationMonitor::reset() {
  innovations_.clear();
  covariances_.clear();
  own_covariances_.clear();
  recent_d2_.clear();
  recent_d2_sum_ = 0.0;
}

void InnovationMonitor::add(const model::Pose2& estimate, const model::Pose2& fix, const Eigen::Matrix3d& fix_covariance,
                            const std::optional<Eigen::Matrix3d>& own_error_covariance) {
  const Eigen::Vector3d delta(fix.x - estimate.x, fix.y - estimate.y, wrap_angle(fix.theta - estimate.theta));
  const Eigen::Matrix3d& own = own_error_covariance ? *own_error_covariance : fix_covariance;
  if (!delta.allFinite() || !fix_covariance.allFinite() || !own.allFinite()) {
    return;
  }
  innovations_.push_back(delta);
  covariances_.push_back(fix_covariance);
  own_covariances_.push_back(own);
  while (innovations_.size() > static_cast<std::size_t>(params_.innovation_window_epochs)) {
    innovations_.pop_front();
    covariances_.pop_front();
    own_covariances_.pop_front();
  }
}

bool InnovationMonitor::typical(Eigen::Vector3d& median_innovation, Eigen::Matrix3d& typical_covariance,
                                const std::deque<Eigen::Matrix3d>& covariances) const {
  const std::size_t needed = std::max<std::size_t>(3, static_cast<std::size_t>(params_.innovation_window_epochs) / 5);
  if (innovations_.size() < needed) {
    return false;
  }
  median_innovation = this->median_innovation(0, innovations_.size());
  // The typical fix's covariance (the one of median trace), not their mean: an outlier fix's own
  // variance (a non-line-of-sight range's leave-one-out residual squared) must not hide the
  // discrepancy, as the median innovation ignores the outlier fix itself.
  std::vector<std::pair<double, std::size_t>> traces;
  traces.reserve(covariances.size());
  for (std::size_t i = 0; i < covariances.size(); ++i) {
    traces.emplace_back(covariances[i].trace(), i);
  }
  std::nth_element(traces.begin(), traces.begin() + static_cast<std::ptrdiff_t>(traces.size() / 2), traces.end());
  typical_covariance = covariances[traces[traces.size() / 2].second];
  return true;
}

Eigen::Vector3d InnovationMonitor::median_innovation(std::size_t first, std::size_t last) const {
  Eigen::Vector3d result;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> values;
    values.reserve(last - first);
    for (std::size_t i = first; i < last; ++i) {
      values.push_back(innovations_[i](c));
    }
    result(c) = median(std::move(values));
  }
  return result;
}

bool InnovationMonitor::lost(const Eigen::Matrix3d& filter_covariance, Eigen::Vector3d& correction,
                             Eigen::Matrix3d& fix_covariance) {
  Eigen::Vector3d typical_innovation;
  Eigen::Matrix3d mean_s;
  if (!typical(typical_innovation, mean_s, own_covariances_)) {
    return false;
  }
  const Eigen::Matrix3d spread = mean_s + filter_covariance;
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(0.5 * (spread + spread.transpose()));
  if (ldlt.info() != Eigen::Success || !spread.allFinite()) {
    return false;
  }
  const double d2 = typical_innovation.dot(ldlt.solve(typical_innovation));
  // A filter may sit a few sigmas off for long while its own covariance grows to nearly excuse
  // it: the time-averaged d^2 (about 3 or less while the filter follows its fixes: the median of
  // correlated fixes is at least as good as one) over lost_window_epochs catches that.
  recent_d2_.push_back(d2);
  recent_d2_sum_ += d2;
  while (recent_d2_.size() > static_cast<std::size_t>(params_.lost_window_epochs)) {
    recent_d2_sum_ -= recent_d2_.front();
    recent_d2_.pop_front();
  }
  const bool persistent = recent_d2_.size() >= static_cast<std::size_t>(params_.lost_window_epochs) / 2 &&
                          recent_d2_sum_ / static_cast<double>(recent_d2_.size()) > params_.lost_mean_d2;
  if (!(d2 > params_.lost_filter_d2) && !persistent) {
    return false;
  }
  correction = typical_innovation;
  fix_covariance = mean_s;
  return true;
}

Eigen::Matrix3d InnovationMonitor::excess(const Eigen::Matrix3d& estimate_covariance) const {
  return unexplained(estimate_covariance, false);
}

Eigen::Matrix3d InnovationMonitor::drifting_excess(const Eigen::Matrix3d& estimate_covariance) const {
  return unexplained(estimate_covariance, true);
}

Eigen::Matrix3d InnovationMonitor::unexplained(const Eigen::Matrix3d& estimate_covariance, bool carry_trend) const {
  Eigen::Vector3d innovation;
  Eigen::Matrix3d mean_s;
  if (!typical(innovation, mean_s, covariances_) || !estimate_covariance.allFinite()) {
    return Eigen::Matrix3d::Zero();
  }
  if (carry_trend) {
    const std::size_t half = innovations_.size() / 2;
    innovation += median_innovation(innovations_.size() - half, innovations_.size()) - median_innovation(0, half);
    innovation(2) = wrap_angle(innovation(2));
  }
  const Eigen::Matrix3d unexplained = innovation * innovation.transpose() - mean_s - estimate_covariance;
  return positive_part(0.5 * (unexplained + unexplained.transpose()));
}

Eigen::Matrix3d positive_part(const Eigen::Matrix3d& m) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(m);  // reads m's lower triangle
  if (eigen.info() != Eigen::Success) {
    return Eigen::Matrix3d::Zero();
  }
  return eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace robodds::uwb_relative_estimator
