#include "components/uwb_relative_estimator/relative_pose_covariance.hpp"

#include <cmath>
#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>

#include "common/angle.hpp"
#include "components/uwb_relative_estimator/median.hpp"
#include "components/uwb_relative_estimator/relative_pose.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

/// 1 / Phi^-1(3/4): the MAD of a normal distribution times this is its std.
constexpr double kMadToStd = 1.4826;

/// x' = inverse(m_i) x m_j as a function of (x, m_i, m_j) stacked in a 9-vector.
Eigen::Vector3d dead_reckon(const Eigen::Matrix<double, 9, 1>& v) {
  const model::Pose2 x{v(0), v(1), v(2)};
  const model::Pose2 own{v(3), v(4), v(5)};
  const model::Pose2 other{v(6), v(7), v(8)};
  const model::Pose2 out = model::compose(model::between(own, x), other);
  return Eigen::Vector3d(out.x, out.y, out.theta);
}

}  // namespace

const params::ParamTable<UncertaintyParams>& uncertainty_param_table() {
  using P = UncertaintyParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>("Reported covariances of every stage (issue 27).")
          .add("range_std_floor_m", &P::range_std_floor_m, "m", params::positive(),
               "floor of the independent per-range std estimated from the residuals (the configured range noise)")
          .add("range_common_std_m", &P::range_common_std_m, "m", params::non_negative(),
               "std of the range error common to all links of a robot pair (one epoch cannot see it)")
          .add("noise_window_epochs", &P::noise_window_epochs, "epochs", params::at_least(1),
               "epochs whose residual std form the running median of the range noise")
          .add("range_common_time_s", &P::range_common_time_s, "s", params::positive(),
               "pf, pf_baseline: time constant of the common-mode range error (how long their measurements' errors stay alike)")
          .add("range_link_time_s", &P::range_link_time_s, "s", params::positive(),
               "pf, pf_baseline: time constant of each link's independent range error (white noise counted as lasting as long)")
          .add("innovation_window_epochs", &P::innovation_window_epochs, "epochs", params::at_least(1),
               "pf, pf_baseline: epochs of eq. (1) fixes whose median innovation, beyond their covariance, widens the filter's")
          .add("node_bias_std_m", &P::node_bias_std_m, "m", params::non_negative(),
               "std of a range bias shared by every link of one UWB node (antenna delay, a shadowed node); the fit absorbs it, so it is configured")
          .add("lost_filter_d2", &P::lost_filter_d2, "", params::positive(),
               "pf, pf_baseline: restart when the fixes' median innovation is this far (squared Mahalanobis, fixes' + filter's covariance)")
          .add("lost_mean_d2", &P::lost_mean_d2, "", params::positive(),
               "pf, pf_baseline: restart also when that squared distance's mean over lost_window_epochs exceeds this")
          .add("lost_window_epochs", &P::lost_window_epochs, "epochs", params::at_least(2),
               "pf, pf_baseline: epochs of the lost-filter test's mean")
          .add("outlier_sigma", &P::outlier_sigma, "", params::positive(),
               "a range whose leave-one-out residual exceeds this many range stds gets its own variance (that residual squared)")
          .add("fix_check_lag_s", &P::fix_check_lag_s, "s", params::non_negative("0 = off"),
               "uwb: each fix against the fix of this long ago dead-reckoned by odometry; what the error model does not explain scales the covariance")
          .add("fix_check_window_epochs", &P::fix_check_window_epochs, "epochs", params::at_least(1),
               "uwb: tests whose mean statistics give the fix-track check's scales");
  return table;
}

void UncertaintyParams::validate() const { uncertainty_param_table().check_ranges(*this); }

namespace {

/// |r_kl - d_kl(pose)| of every range.
std::vector<double> absolute_residuals(const model::UwbArray& own, const model::UwbArray& other,
                                       const Eigen::MatrixXd& ranges_m, const model::Pose2& pose) {
  std::vector<double> absolute;
  absolute.reserve(static_cast<std::size_t>(ranges_m.size()));
  for (Eigen::Index k = 0; k < ranges_m.rows(); ++k) {
    for (Eigen::Index l = 0; l < ranges_m.cols(); ++l) {
      absolute.push_back(std::abs(ranges_m(k, l) - predicted_range(pose, own.nodes_m[static_cast<std::size_t>(k)],
                                                                   other.nodes_m[static_cast<std::size_t>(l)])));
    }
  }
  return absolute;
}

}  // namespace

double robust_residual_std_m(const model::UwbArray& own, const model::UwbArray& other, const Eigen::MatrixXd& ranges_m,
                             const model::Pose2& pose) {
  const std::size_t n = static_cast<std::size_t>(ranges_m.size());
  if (n <= 3) {
    return 0.0;
  }
  return kMadToStd * median(absolute_residuals(own, other, ranges_m, pose)) *
         std::sqrt(static_cast<double>(n) / static_cast<double>(n - 3));
}

double residual_rms_std_m(const model::UwbArray& own, const model::UwbArray& other, const Eigen::MatrixXd& ranges_m,
                          const model::Pose2& pose) {
  const std::size_t n = static_cast<std::size_t>(ranges_m.size());
  if (n <= 3) {
    return 0.0;
  }
  double sum = 0.0;
  for (const double r : absolute_residuals(own, other, ranges_m, pose)) {
    sum += r * r;
  }
  return std::sqrt(sum / static_cast<double>(n - 3));
}

namespace {

/// The K L x 3 Jacobian of the predicted ranges at `pose`; false at coincident nodes (no gradient).
bool range_jacobian(const model::UwbArray& own, const model::UwbArray& other, const model::Pose2& pose,
                    Eigen::MatrixXd& jacobian) {
  const Eigen::Index n = static_cast<Eigen::Index>(own.nodes_m.size() * other.nodes_m.size());
  jacobian.resize(n, 3);
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  Eigen::Index row = 0;
  for (const Eigen::Vector2d& node_i : own.nodes_m) {
    for (const Eigen::Vector2d& node_j : other.nodes_m) {
      // d = |p|, p = t + R(theta) n_j - n_i: dd/dt = p / d, dd/dtheta = p . (dR/dtheta n_j) / d.
      const Eigen::Vector2d rotated_derivative(-s * node_j.x() - c * node_j.y(), c * node_j.x() - s * node_j.y());
      const Eigen::Vector2d p(pose.x + c * node_j.x() - s * node_j.y() - node_i.x(),
                              pose.y + s * node_j.x() + c * node_j.y() - node_i.y());
      const double d = p.norm();
      if (!(d > 0.0)) {
        return false;
      }
      jacobian.row(row++) << p.x() / d, p.y() / d, p.dot(rotated_derivative) / d;
    }
  }
  return true;
}

/// (J^T J)^-1; false when singular or too ill-conditioned to mean anything in double precision.
bool information_inverse(const Eigen::MatrixXd& jacobian, Eigen::Matrix3d& inverse) {
  const Eigen::Matrix3d information = jacobian.transpose() * jacobian;
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(information);
  // A condition number beyond ~1e12 leaves (J^T J)^-1 meaningless in double precision.
  const Eigen::Vector3d d = ldlt.vectorD().cwiseAbs();
  if (ldlt.info() != Eigen::Success || !(d.minCoeff() > 1e-12 * d.maxCoeff())) {
    return false;
  }
  inverse = ldlt.solve(Eigen::Matrix3d::Identity());
  return true;
}

}  // namespace

Eigen::Matrix3d range_fix_covariance(const model::UwbArray& own, const model::UwbArray& other, const model::Pose2& pose,
                                     double independent_std_m, double common_std_m) {
  Eigen::MatrixXd jacobian;
  Eigen::Matrix3d inverse;
  if (!range_jacobian(own, other, pose, jacobian) || !information_inverse(jacobian, inverse)) {
    return Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  const Eigen::Vector3d common_shift = inverse * (jacobian.transpose() * Eigen::VectorXd::Ones(jacobian.rows()));
  return independent_std_m * independent_std_m * inverse +
         common_std_m * common_std_m * common_shift * common_shift.transpose();
}

Eigen::Matrix3d RangeErrorMap::covariance() const {
  Eigen::Matrix3d out = independent_map * independent_variance_m2.asDiagonal() * independent_map.transpose() +
                        common_std_m * common_std_m * common_map * common_map.transpose();
  if (node_map.cols() > 0) {
    out += node_bias_std_m * node_bias_std_m * node_map * node_map.transpose();
  }
  return out;
}

bool range_error_map(const model::UwbArray& own, const model::UwbArray& other, const model::Pose2& pose,
                     double independent_std_m, double common_std_m, RangeErrorMap& out, double node_bias_std_m) {
  Eigen::MatrixXd jacobian;
  Eigen::Matrix3d inverse;
  if (!range_jacobian(own, other, pose, jacobian) || !information_inverse(jacobian, inverse)) {
    return false;
  }
  out.independent_map = inverse * jacobian.transpose();
  out.common_map = out.independent_map.rowwise().sum();
  // Node patterns, centred per array: link (k, l) is row k L + l.
  const Eigen::Index nk = static_cast<Eigen::Index>(own.nodes_m.size());
  const Eigen::Index nl = static_cast<Eigen::Index>(other.nodes_m.size());
  Eigen::MatrixXd patterns = Eigen::MatrixXd::Zero(nk * nl, nk + nl);
  for (Eigen::Index k = 0; k < nk; ++k) {
    for (Eigen::Index l = 0; l < nl; ++l) {
      patterns.row(k * nl + l).head(nk).setConstant(-1.0 / static_cast<double>(nk));
      patterns.row(k * nl + l).tail(nl).setConstant(-1.0 / static_cast<double>(nl));
      patterns(k * nl + l, k) += 1.0;
      patterns(k * nl + l, nk + l) += 1.0;
    }
  }
  out.node_map = out.independent_map * patterns;
  out.node_bias_std_m = node_bias_std_m;
  out.independent_variance_m2 = Eigen::VectorXd::Constant(jacobian.rows(), independent_std_m * independent_std_m);
  out.common_std_m = common_std_m;
  return true;
}

Eigen::VectorXd range_error_variances(const model::UwbArray& own, const model::UwbArray& other,
                                      const Eigen::MatrixXd& ranges_m, const model::Pose2& pose, double base_std_m,
                                      double detect_std_m, double outlier_sigma) {
  const Eigen::Index n = ranges_m.size();
  Eigen::VectorXd variances = Eigen::VectorXd::Constant(n, base_std_m * base_std_m);
  Eigen::MatrixXd jacobian;
  Eigen::Matrix3d inverse;
  if (!range_jacobian(own, other, pose, jacobian) || !information_inverse(jacobian, inverse)) {
    return variances;
  }
  const double limit = outlier_sigma * detect_std_m;
  Eigen::Index row = 0;
  for (Eigen::Index k = 0; k < ranges_m.rows(); ++k) {
    for (Eigen::Index l = 0; l < ranges_m.cols(); ++l, ++row) {
      const double residual = ranges_m(k, l) - predicted_range(pose, own.nodes_m[static_cast<std::size_t>(k)],
                                                               other.nodes_m[static_cast<std::size_t>(l)]);
      const double leverage = jacobian.row(row) * inverse * jacobian.row(row).transpose();
      // h_k < 1 with more ranges than unknowns; a range the fit follows completely says nothing.
      const double left_out = residual / std::max(1.0 - leverage, 1e-3);
      if (std::abs(left_out) > limit) {
        variances(row) = std::max(variances(row), left_out * left_out);
      }
    }
  }
  return variances;
}

Eigen::Matrix3d with_bearing_curvature(const Eigen::Matrix3d& covariance, const model::Pose2& pose) {
  const Eigen::Vector2d p(pose.x, pose.y);
  const double range = p.norm();
  if (!(range > 0.0) || !covariance.allFinite()) {
    return covariance;
  }
  const Eigen::Vector2d radial = p / range;
  const Eigen::Vector2d tangential(-radial.y(), radial.x());
  const double bearing_variance = std::min(1.0, tangential.dot(covariance.topLeftCorner<2, 2>() * tangential) / (range * range));
  Eigen::Matrix3d out = covariance;
  out.topLeftCorner<2, 2>() += 0.75 * range * range * bearing_variance * bearing_variance * radial * radial.transpose();
  return out;
}

Eigen::Matrix<double, 3, 9> relative_motion_jacobian(const model::Pose2& x, const model::Pose2& own_increment,
                                                     const model::Pose2& other_increment) {
  Eigen::Matrix<double, 9, 1> v;
  v << x.x, x.y, x.theta, own_increment.x, own_increment.y, own_increment.theta, other_increment.x, other_increment.y,
      other_increment.theta;
  // Central differences: the map is smooth and cheap; 1e-6 (m, rad) keeps the truncation and the
  // rounding error both near 1e-10.
  constexpr double h = 1e-6;
  Eigen::Matrix<double, 3, 9> jacobian;
  for (int c = 0; c < 9; ++c) {
    Eigen::Matrix<double, 9, 1> plus = v;
    Eigen::Matrix<double, 9, 1> minus = v;
    plus(c) += h;
    minus(c) -= h;
    Eigen::Vector3d difference = dead_reckon(plus) - dead_reckon(minus);
    difference(2) = wrap_angle(difference(2));
    jacobian.col(c) = difference / (2.0 * h);
  }
  return jacobian;
}

Eigen::Matrix3d propagate_relative_covariance(const Eigen::Matrix3d& covariance, const model::Pose2& x,
                                              const model::Pose2& own_increment, const model::Pose2& other_increment,
                                              double xy_std_m, double theta_std_rad) {
  const Eigen::Matrix<double, 3, 9> jacobian = relative_motion_jacobian(x, own_increment, other_increment);
  Eigen::Matrix<double, 9, 9> input = Eigen::Matrix<double, 9, 9>::Zero();
  input.topLeftCorner<3, 3>() = covariance;
  const Eigen::Vector3d increment_variance(xy_std_m * xy_std_m, xy_std_m * xy_std_m, theta_std_rad * theta_std_rad);
  input.block<3, 3>(3, 3) = increment_variance.asDiagonal();
  input.block<3, 3>(6, 6) = increment_variance.asDiagonal();
  const Eigen::Matrix3d out = jacobian * input * jacobian.transpose();
  return 0.5 * (out + out.transpose());  // symmetric to the last bit
}

RangeNoiseLevel::RangeNoiseLevel(const UncertaintyParams& params) : params_(params) { params_.validate(); }

void RangeNoiseLevel::add(double residual_std_m) {
  recent_.push_back(residual_std_m);
  while (recent_.size() > static_cast<std::size_t>(params_.noise_window_epochs)) {
    recent_.pop_front();
  }
}

double RangeNoiseLevel::std_m() const {
  if (recent_.empty()) {
    return params_.range_std_floor_m;
  }
  return std::max(params_.range_std_floor_m, median(std::vector<double>(recent_.begin(), recent_.end())));
}

}  // namespace robodds::uwb_relative_estimator
