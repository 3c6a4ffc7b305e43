#include "components/route_follower/route_follower.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/angle.hpp"
#include "common/number_text.hpp"
#include "components/route_follower/route_law.hpp"

namespace robodds::route_follower {

RouteFollower::RouteFollower(const RouteParams& params) : params_(params) {
  params_.validate();
  for (const params::Point2& p : params_.route) {
    vertices_.emplace_back(p[0], p[1]);
  }
}

void RouteFollower::advance() {
  ++reached_;
  segment_start_ = vertices_[target_];
  if (target_ + 1 < vertices_.size()) {
    ++target_;
  } else if (params_.loop) {
    target_ = 0;
  } else {
    phase_ = Phase::kDone;
    return;
  }
  phase_ = Phase::kTurning;
}

model::Twist RouteFollower::drive(const model::Pose2& pose, const Eigen::Vector2d& position, double distance_m,
                                  double dt_s, FollowerStatus& status) const {
  const SegmentError error = segment_error(position, segment_start_, vertices_[target_]);
  status.cross_track_m = error.cross_track_m;
  const double desired = line_following_heading(error, params_.lookahead_m);
  // Never beyond the vertex within one period (matters only for a tolerance below speed * dt).
  return model::Twist{std::min(params_.speed_mps, distance_m / dt_s), line_following_rate(desired, pose.theta, params_)};
}

FollowerOutput RouteFollower::step(const model::Pose2& pose, double dt_s) {
  if (!std::isfinite(pose.x) || !std::isfinite(pose.y) || !std::isfinite(pose.theta)) {
    throw std::invalid_argument("route follower: the pose is not finite (got " + model::to_text(pose) + ")");
  }
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    throw std::invalid_argument("route follower: dt_s must be > 0 and finite (got " + shortest_text(dt_s) + ")");
  }
  const Eigen::Vector2d position(pose.x, pose.y);
  if (!started_) {
    segment_start_ = position;
    started_ = true;
  }
  FollowerOutput out;
  FollowerStatus& status = out.status;
  if (phase_ != Phase::kDone && (vertices_[target_] - position).norm() <= params_.position_tolerance_m) {
    advance();
    status.reached_this_step = true;
  }
  const Eigen::Vector2d to_target = vertices_[target_] - position;
  const double distance = to_target.norm();
  const double bearing_error = wrap_angle(std::atan2(to_target.y(), to_target.x()) - pose.theta);
  status.distance_to_target_m = distance;
  status.heading_error_rad = bearing_error;
  status.cross_track_m = segment_error(position, segment_start_, vertices_[target_]).cross_track_m;
  if (phase_ == Phase::kTurning && std::abs(bearing_error) <= params_.heading_tolerance_rad) {
    phase_ = Phase::kDriving;
  } else if (phase_ == Phase::kDriving && std::abs(bearing_error) > params_.realign_threshold_rad) {
    phase_ = Phase::kTurning;  // off course (or past the vertex beside the tolerance circle): stop and face it
  }
  if (phase_ == Phase::kTurning) {
    out.twist = model::Twist{0.0, turn_in_place_rate(bearing_error, params_.turn_rate_radps, dt_s)};
  } else if (phase_ == Phase::kDriving) {
    out.twist = drive(pose, position, distance, dt_s, status);
  }
  // The law stays within the limits by construction (max_correction <= turn_rate); the clamp makes
  // the promise independent of that.
  out.twist = model::saturate(out.twist, model::TwistLimits{params_.speed_mps, params_.turn_rate_radps});
  status.phase = phase_;
  status.target_index = target_;
  status.reached_count = reached_;
  return out;
}

}  // namespace robodds::route_follower
