#include "components/uwb_relative_estimator/relative_pf_likelihood.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "common/angle.hpp"
#include "common/param_checks.hpp"
#include "components/uwb_relative_estimator/relative_pose.hpp"

namespace robodds::uwb_relative_estimator {

double pose_log_likelihood(const model::Pose2& particle, const model::Pose2& measured, double lambda_d_m,
                           double lambda_theta_rad) {
  const double dx = measured.x - particle.x;
  const double dy = measured.y - particle.y;
  const double dtheta = wrap_angle(measured.theta - particle.theta);
  return -0.5 * ((dx * dx + dy * dy) / (lambda_d_m * lambda_d_m) + dtheta * dtheta / (lambda_theta_rad * lambda_theta_rad));
}

double range_log_likelihood(const model::Pose2& particle, const model::UwbArray& own, const model::UwbArray& other,
                            const Eigen::MatrixXd& ranges_m, double range_std_m) {
  // predicted_range's arithmetic, in its order (bit for bit the same), with the particle's sin and
  // cos taken once instead of once per range (issue 29: they were most of the baseline's update).
  const double c = std::cos(particle.theta);
  const double s = std::sin(particle.theta);
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < own.nodes_m.size(); ++k) {
    const Eigen::Vector2d& node_i = own.nodes_m[k];
    for (std::size_t l = 0; l < other.nodes_m.size(); ++l) {
      const Eigen::Vector2d& node_j = other.nodes_m[l];
      const double dx = particle.x + c * node_j.x() - s * node_j.y() - node_i.x();
      const double dy = particle.y + s * node_j.x() + c * node_j.y() - node_i.y();
      const double residual =
          ranges_m(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l)) - std::sqrt(dx * dx + dy * dy);
      sum_sq += residual * residual;
    }
  }
  return -0.5 * sum_sq / (range_std_m * range_std_m);
}

void require_finite_pose(const char* caller, const model::Pose2& pose) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    throw std::invalid_argument(std::string(caller) + ": measured pose is not finite (got " + model::to_text(pose) + ")");
  }
}


}  // namespace robodds::uwb_relative_estimator
