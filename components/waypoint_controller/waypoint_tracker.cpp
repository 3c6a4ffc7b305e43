#include "components/waypoint_controller/waypoint_tracker.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include <Eigen/Cholesky>

#include "common/model/actuator.hpp"
#include "common/number_text.hpp"
#include "components/waypoint_controller/path_law.hpp"
#include "components/waypoint_controller/polar.hpp"

namespace robodds::waypoint_controller {
namespace {

void require_valid_mission(const std::vector<Eigen::Vector2d>& waypoints_m) {
  if (waypoints_m.empty()) {
    throw std::invalid_argument("set_mission: the mission is empty (needs at least one way-point)");
  }
  for (std::size_t i = 0; i < waypoints_m.size(); ++i) {
    if (!waypoints_m[i].allFinite()) {
      throw std::invalid_argument("set_mission: way-point " + std::to_string(i) + " is not finite (got (" +
                                  shortest_text(waypoints_m[i].x()) + ", " + shortest_text(waypoints_m[i].y()) +
                                  "))");
    }
  }
}

void require_finite_pose(double x_m, double y_m, double theta_rad) {
  if (!std::isfinite(x_m) || !std::isfinite(y_m) || !std::isfinite(theta_rad)) {
    throw std::invalid_argument("step: the pose estimate is not finite (got x=" + shortest_text(x_m) +
                                ", y=" + shortest_text(y_m) + ", theta=" + shortest_text(theta_rad) + ")");
  }
}

}  // namespace

WaypointTracker::WaypointTracker(const ControllerParams& params, double period_s) : params_(params), period_s_(period_s) {
  params_.validate();
  const bool accel_limited = params_.body.actuator.max_accel_mps2 > 0.0 || params_.body.actuator.max_angular_accel_radps2 > 0.0;
  if (accel_limited && !(period_s_ > 0.0 && std::isfinite(period_s_))) {
    throw std::invalid_argument("period_s: must be > 0 and finite with max_accel_mps2 or max_angular_accel_radps2 set (got " +
                                shortest_text(period_s_) + ")");
  }
}

void WaypointTracker::set_mission(std::vector<Eigen::Vector2d> waypoints_m) {
  require_valid_mission(waypoints_m);
  mission_ = std::move(waypoints_m);
  target_index_ = 0;
  done_ = false;
  has_segment_start_ = false;
  reach_distances_m_.clear();
  reach_distances_m_.reserve(mission_.size());  // keeps step() allocation-free
}

Command WaypointTracker::ramp(const Command& wanted) {
  const model::Twist reachable = model::limit_acceleration(model::Twist{wanted.v, wanted.omega},
                                                           model::Twist{last_command_.v, last_command_.omega}, period_s_,
                                                           params_.body.actuator);
  last_command_ = period_s_ > 0.0 ? Command{reachable.v, reachable.omega} : wanted;
  return last_command_;
}

Command WaypointTracker::hold(const Command& wanted) {
  const model::Twist limited = model::scale_to_wheel_limit(
      model::saturate(model::Twist{wanted.v, wanted.omega}, model::TwistLimits{params_.max_speed_mps, params_.max_turn_rate_radps}),
      params_.body.wheel_base_m, params_.body.actuator.max_wheel_speed_mps);
  return ramp(Command{limited.v, limited.omega});
}

TrackerOutput WaypointTracker::step(double x_m, double y_m, double theta_rad) {
  return step_impl(x_m, y_m, theta_rad, nullptr);
}

TrackerOutput WaypointTracker::step(double x_m, double y_m, double theta_rad, const Eigen::Matrix2d& position_covariance_m2) {
  return step_impl(x_m, y_m, theta_rad, &position_covariance_m2);
}

bool WaypointTracker::inside_confidence_ellipse(const Eigen::Vector2d& offset_m, const Eigen::Matrix2d* covariance_m2) const {
  const double kappa = params_.confidence_switch_sigmas;
  if (!(kappa > 0.0) || covariance_m2 == nullptr || !covariance_m2->allFinite()) {
    return false;
  }
  const Eigen::LLT<Eigen::Matrix2d> cholesky(*covariance_m2);
  if (cholesky.info() != Eigen::Success) {
    return false;  // not positive definite: no usable confidence
  }
  const double mahalanobis_squared = offset_m.dot(cholesky.solve(offset_m));
  return mahalanobis_squared <= kappa * kappa;
}

TrackerOutput WaypointTracker::step_impl(double x_m, double y_m, double theta_rad, const Eigen::Matrix2d* position_covariance_m2) {
  require_finite_pose(x_m, y_m, theta_rad);
  if (!has_mission()) {
    throw std::logic_error("step: no mission (call set_mission first)");
  }
  const Eigen::Vector2d position(x_m, y_m);
  TrackerOutput output;
  TrackerStatus& status = output.status;
  if (!has_segment_start_) {
    segment_start_m_ = position;
    has_segment_start_ = true;
  }

  // Eq. (19): chi = k+1 when ||p - W_k|| <= epsilon, chi = n at the last way-point.
  const Eigen::Vector2d offset = mission_[target_index_] - position;
  const double distance_before_switch = offset.norm();
  if (!done_ && (distance_before_switch <= params_.epsilon_m || inside_confidence_ellipse(offset, position_covariance_m2))) {
    reach_distances_m_.push_back(distance_before_switch);
    status.reached_this_step = true;
    status.reached_distance_m = distance_before_switch;
    if (target_index_ + 1 < mission_.size()) {
      segment_start_m_ = mission_[target_index_];
      ++target_index_;
    } else {
      done_ = true;
    }
  }

  const PolarError error = polar_error(position, theta_rad, mission_[target_index_]);
  Command wanted;
  if (!(done_ && params_.stop_when_done)) {
    wanted = params_.path_lookahead_m > 0.0
                 ? path_command(path_error(segment_start_m_, mission_[target_index_], position, theta_rad,
                                           params_.path_lookahead_m),
                                params_)
                 : waypoint_command(error, params_);
  }
  output.command = ramp(wanted);

  status.target_index = target_index_;
  status.reached_count = reach_distances_m_.size();
  status.distance_to_target_m = error.distance_m;
  status.distance_to_final_m = (mission_.back() - position).norm();
  status.alpha_rad = error.alpha_rad;
  status.sigma_rad = error.sigma_rad;
  status.done = done_;
  return output;
}

}  // namespace robodds::waypoint_controller
