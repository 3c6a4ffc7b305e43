#pragma once
// Storage of the particle states: one Eigen array per state component (structure of arrays),
// so the weight update and the statistics run as vectorised array expressions.

#include <Eigen/Core>

namespace robodds::pf_estimator {

struct ParticleSet {
  Eigen::ArrayXd x;      // m, world frame
  Eigen::ArrayXd y;      // m, world frame
  Eigen::ArrayXd theta;  // rad, heading counter-clockwise from world +x, wrapped to (-pi, pi]

  Eigen::Index size() const { return x.size(); }

  void resize(Eigen::Index count) {
    x.resize(count);
    y.resize(count);
    theta.resize(count);
  }
};

}  // namespace robodds::pf_estimator
