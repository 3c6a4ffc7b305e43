#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::uwb_relative_estimator {
/// sensor/uwb (robot, peer) and sensor/odometry of the robot and its peers in; for each served
/// robot and peer, one RelativePoseEstimate per stage out (estimate/relative_pose = the particle
/// filter, estimate/relative_pose_{uwb,window,pf_baseline,odometry}), at rate_hz.
std::unique_ptr<Component> make_uwb_relative_estimator_node();
}  // namespace robodds::uwb_relative_estimator
