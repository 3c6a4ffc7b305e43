#include "components/uwb_relative_pose/relative_pf_likelihood.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "common/angle.hpp"
#include "common/param_checks.hpp"
#include "components/uwb_relative_pose/relative_pose.hpp"

namespace robodds::uwb {

double pose_log_likelihood(const model::Pose2& particle, const model::Pose2& measured, double lambda_d_m,
                           double lambda_theta_rad) {
  const double dx = measured.x - particle.x;
  const double dy = measured.y - particle.y;
  const double dtheta = wrap_angle(measured.theta - particle.theta);
  return -0.5 * ((dx * dx + dy * dy) / (lambda_d_m * lambda_d_m) + dtheta * dtheta / (lambda_theta_rad * lambda_theta_rad));
}

double range_log_likelihood(const model::Pose2& particle, const model::UwbArray& own, const model::UwbArray& other,
                            const Eigen::MatrixXd& ranges_m, double range_std_m) {
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < own.nodes_m.size(); ++k) {
    for (std::size_t l = 0; l < other.nodes_m.size(); ++l) {
      const double residual = ranges_m(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l)) -
                              predicted_range(particle, own.nodes_m[k], other.nodes_m[l]);
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

void require_valid_ranges(const char* caller, const model::UwbArray& own, const model::UwbArray& other,
                          const Eigen::MatrixXd& ranges_m) {
  if (own.nodes_m.empty() || other.nodes_m.empty()) {
    throw std::invalid_argument(std::string(caller) + ": both arrays need at least one node (got " +
                                std::to_string(own.nodes_m.size()) + " and " + std::to_string(other.nodes_m.size()) + ")");
  }
  if (ranges_m.rows() != static_cast<Eigen::Index>(own.nodes_m.size()) ||
      ranges_m.cols() != static_cast<Eigen::Index>(other.nodes_m.size())) {
    throw std::invalid_argument(std::string(caller) + ": ranges are " + std::to_string(ranges_m.rows()) + " x " +
                                std::to_string(ranges_m.cols()) + ", the arrays need " +
                                std::to_string(own.nodes_m.size()) + " x " + std::to_string(other.nodes_m.size()));
  }
  for (Eigen::Index k = 0; k < ranges_m.rows(); ++k) {
    for (Eigen::Index l = 0; l < ranges_m.cols(); ++l) {
      if (!(ranges_m(k, l) >= 0.0) || !std::isfinite(ranges_m(k, l))) {
        param_checks::reject(std::string(caller) + ": range (" + std::to_string(k) + ", " + std::to_string(l) + ")",
                             "must be >= 0 and finite", ranges_m(k, l));
      }
    }
  }
}

}  // namespace robodds::uwb
