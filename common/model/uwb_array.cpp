#include "common/model/uwb_array.hpp"

#include <cmath>
#include <string>

#include "common/number_text.hpp"
#include "common/param_checks.hpp"

namespace robodds::model {

UwbArray square_array(double side_m) {
  param_checks::require_positive("side_m", side_m);
  const double h = 0.5 * side_m;
  return UwbArray{{{h, h}, {-h, h}, {-h, -h}, {h, -h}}};
}

void check_array(std::string_view key, const UwbArray& array) {
  const std::size_t n = array.nodes_m.size();
  if (n < 3) {
    param_checks::reject(key, "needs at least 3 nodes (a relative heading needs them)", std::to_string(n) + " nodes");
  }
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d& p = array.nodes_m[k];
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) {
      param_checks::reject(key, "node " + std::to_string(k) + " must have finite coordinates",
                           "[" + shortest_text(p.x()) + ", " + shortest_text(p.y()) + "]");
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t l = k + 1; l < n; ++l) {
      const double spacing = (array.nodes_m[k] - array.nodes_m[l]).norm();
      if (!(spacing >= kMinNodeSpacingM)) {
        param_checks::reject(key,
                             "nodes " + std::to_string(k) + " and " + std::to_string(l) + " coincide (closer than " +
                                 shortest_text(kMinNodeSpacingM) + " m)",
                             shortest_text(spacing) + " m apart");
      }
    }
  }
}

Eigen::Vector2d node_in_world(const Pose2& pose, const Eigen::Vector2d& node_m) {
  const double c = std::cos(pose.theta);
  const double s = std::sin(pose.theta);
  return {pose.x + c * node_m.x() - s * node_m.y(), pose.y + s * node_m.x() + c * node_m.y()};
}

Eigen::MatrixXd array_ranges(const UwbArray& a, const Pose2& pose_a, const UwbArray& b, const Pose2& pose_b) {
  const auto rows = static_cast<Eigen::Index>(a.nodes_m.size());
  const auto cols = static_cast<Eigen::Index>(b.nodes_m.size());
  Eigen::MatrixXd ranges(rows, cols);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const Eigen::Vector2d pk = node_in_world(pose_a, a.nodes_m[static_cast<std::size_t>(k)]);
    for (Eigen::Index l = 0; l < cols; ++l) {
      ranges(k, l) = (pk - node_in_world(pose_b, b.nodes_m[static_cast<std::size_t>(l)])).norm();
    }
  }
  return ranges;
}

}  // namespace robodds::model
