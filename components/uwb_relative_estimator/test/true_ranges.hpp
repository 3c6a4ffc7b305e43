#pragma once
// Test support: the noise-free ranges between two UWB arrays at a relative pose (the tests'
// ground truth for the solver and its covariance).
#include <Eigen/Core>

#include "common/model/pose2.hpp"
#include "components/uwb_relative_estimator/relative_pose.hpp"

namespace robodds::uwb_relative_estimator::testing {

/// ranges(k, l): node k of `own` to node l of `other`, `other` at `pose` in own's frame (m).
inline Eigen::MatrixXd true_ranges(const UwbArray& own, const UwbArray& other, const model::Pose2& pose) {
  Eigen::MatrixXd ranges(own.nodes_m.size(), other.nodes_m.size());
  for (std::size_t k = 0; k < own.nodes_m.size(); ++k) {
    for (std::size_t l = 0; l < other.nodes_m.size(); ++l) {
      ranges(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(l)) = predicted_range(pose, own.nodes_m[k], other.nodes_m[l]);
    }
  }
  return ranges;
}

}  // namespace robodds::uwb_relative_estimator::testing
