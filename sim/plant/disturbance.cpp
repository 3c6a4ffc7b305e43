#include "sim/plant/disturbance.hpp"

#include "common/angle.hpp"

namespace robodds::plant {

bool PoseDisturbance::due(double time_s, bool already_applied) const {
  constexpr double kToleranceS = 1e-9;
  return enabled() && !already_applied && time_s >= at_s - kToleranceS;
}

model::Pose2 apply_disturbance(const model::Pose2& pose, const PoseDisturbance& disturbance) {
  return model::Pose2{pose.x + disturbance.dx_m, pose.y + disturbance.dy_m, wrap_angle(pose.theta + disturbance.dtheta_rad)};
}

}  // namespace robodds::plant
