#include "components/uwb_relative_estimator/fix_track_check.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Cholesky>

#include "common/angle.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

constexpr double kMaxStat = 100.0;
/// The 99 % quantiles of chi-square with 2 and 1 degrees of freedom: this epoch's fix alone is
/// judged off when its test exceeds them (1 % of the fixes of a model that holds).
constexpr double kPositionGate = 9.210;
constexpr double kHeadingGate = 6.635;

bool finite(const model::Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }

}  // namespace

FixTrackCheck::FixTrackCheck(const UncertaintyParams& params) : params_(params) { params_.validate(); }

void FixTrackCheck::reset() {
  kept_.clear();
  recent_.clear();
  recent_sum_.setZero();
  last_.setZero();
  tests_ = 0;
}

void FixTrackCheck::predict(const model::Pose2& own_increment, const model::Pose2& other_increment, double xy_std_m,
                            double theta_std_rad) {
  const Eigen::Vector3d increment_variance(xy_std_m * xy_std_m, xy_std_m * xy_std_m, theta_std_rad * theta_std_rad);
  for (Kept& kept : kept_) {
    const Eigen::Matrix<double, 3, 9> jacobian = relative_motion_jacobian(kept.pose, own_increment, other_increment);
    const Eigen::Matrix3d f = jacobian.leftCols<3>();
    const Eigen::Matrix3d odometry =
        f * kept.odometry * f.transpose() +
        jacobian.middleCols<3>(3) * increment_variance.asDiagonal() * jacobian.middleCols<3>(3).transpose() +
        jacobian.rightCols<3>() * increment_variance.asDiagonal() * jacobian.rightCols<3>().transpose();
    kept.odometry = 0.5 * (odometry + odometry.transpose());
    kept.propagation = f * kept.propagation;
    kept.pose = model::compose(model::between(own_increment, kept.pose), other_increment);
  }
}

void FixTrackCheck::add(double time_s, const model::Pose2& fix, const RangeErrorMap& error,
                        const Eigen::Matrix3d& covariance) {
  if (params_.fix_check_lag_s <= 0.0 || !std::isfinite(time_s) || !finite(fix) || !covariance.allFinite()) {
    return;
  }
  last_.setZero();
  const double lag = params_.fix_check_lag_s;
  // The oldest kept fix at least one lag old is the reference; older ones are no longer needed.
  while (kept_.size() >= 2 && time_s - kept_[1].time_s >= lag) {
    kept_.pop_front();
  }
  if (!kept_.empty()) {
    const double age = time_s - kept_.front().time_s;
    if (age >= lag && age <= 2.0 * lag) {
      test(time_s, fix, error, covariance, kept_.front());
    }
  }
  // Fixes are kept every twentieth of the lag (each is dead-reckoned every epoch: 20 of them
  // cost what 20 compositions do, whatever the lag), so the reference is 1 to 1.05 lags old.
  if (!kept_.empty() && time_s - kept_.back().time_s < lag / 20.0 - 1e-9) {
    return;
  }
  Kept kept;
  kept.time_s = time_s;
  kept.pose = fix;
  kept.error = error;
  kept.covariance = covariance;
  kept_.push_back(std::move(kept));
}

void FixTrackCheck::test(double time_s, const model::Pose2& fix, const RangeErrorMap& error,
                         const Eigen::Matrix3d& covariance, const Kept& old) {
  const double age = time_s - old.time_s;
  const double rho_link = std::exp(-age / params_.range_link_time_s);
  const double rho_common = std::exp(-age / params_.range_common_time_s);
  // E[e_t e_old^T]: the parts of both fixes' errors that the error model says persist over the lag.
  Eigen::Matrix3d shared = rho_common * error.common_std_m * old.error.common_std_m *
                           (error.common_map * old.error.common_map.transpose());
  if (error.independent_map.cols() == old.error.independent_map.cols() &&
      error.independent_variance_m2.size() == error.independent_map.cols() &&
      old.error.independent_variance_m2.size() == error.independent_map.cols()) {
    const Eigen::VectorXd stds = error.independent_variance_m2.cwiseProduct(old.error.independent_variance_m2).cwiseSqrt();
    shared += rho_link * (error.independent_map * stds.asDiagonal() * old.error.independent_map.transpose());
  }
  if (error.node_map.cols() > 0 && error.node_map.cols() == old.error.node_map.cols()) {
    // A node's bias counted as lasting as the common mode (as FilterErrorCovariance does).
    shared += rho_common * error.node_bias_std_m * old.error.node_bias_std_m *
              (error.node_map * old.error.node_map.transpose());
  }
  const Eigen::Matrix3d cross = shared * old.propagation.transpose();
  Eigen::Matrix3d s = covariance + old.propagation * old.covariance * old.propagation.transpose() + old.odometry -
                      cross - cross.transpose();
  s = 0.5 * (s + s.transpose());
  const Eigen::Vector3d nu(fix.x - old.pose.x, fix.y - old.pose.y, wrap_angle(fix.theta - old.pose.theta));
  const Eigen::LLT<Eigen::Matrix2d> position(s.topLeftCorner<2, 2>());
  if (!nu.allFinite() || position.info() != Eigen::Success || !(s(2, 2) > 0.0)) {
    return;  // the model's difference has no spread to test against (degenerate): no test
  }
  // Each test's statistic clipped at kMaxStat: one wrong fix (a flipped solve) raises the mean of
  // the window by at most kMaxStat / window, an error that lasts raises it all the same.
  const Eigen::Vector2d stat(std::min(kMaxStat, nu.head<2>().dot(position.solve(nu.head<2>()))),
                             std::min(kMaxStat, nu.z() * nu.z() / s(2, 2)));
  last_ = stat;
  recent_.push_back(stat);
  recent_sum_ += stat;
  while (recent_.size() > static_cast<std::size_t>(params_.fix_check_window_epochs)) {
    recent_sum_ -= recent_.front();
    recent_.pop_front();
  }
  ++tests_;
}

double FixTrackCheck::position_scale() const {
  if (recent_.empty()) {
    return 1.0;
  }
  const double epoch = last_.x() > kPositionGate ? last_.x() / 2.0 : 1.0;
  return std::max({1.0, recent_sum_.x() / static_cast<double>(recent_.size()) / 2.0, epoch});
}

double FixTrackCheck::heading_scale() const {
  if (recent_.empty()) {
    return 1.0;
  }
  const double epoch = last_.y() > kHeadingGate ? last_.y() : 1.0;
  return std::max({1.0, recent_sum_.y() / static_cast<double>(recent_.size()), epoch});
}

Eigen::Matrix3d FixTrackCheck::inflate(const Eigen::Matrix3d& covariance) const {
  const double p = std::sqrt(position_scale());
  const Eigen::Vector3d scale(p, p, std::sqrt(heading_scale()));
  return scale.asDiagonal() * covariance * scale.asDiagonal();
}

}  // namespace robodds::uwb_relative_estimator
