// Adapter: PoseEstimate/WaypointMission <-> WaypointTracker <-> VelocityCommand/ControllerStatus.
#include "components/waypoint_controller/node/waypoint_controller_node.hpp"

#include <map>
#include <set>
#include <string>

#include "components/waypoint_controller/waypoint_tracker.hpp"
#include "robodds/idl/robodds.h"
#include "components/waypoint_controller/node/waypoint_controller_params.hpp"
#include "runtime/base/log.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"
#include "system/robot_facts.hpp"

namespace robodds::waypoint_controller {
namespace {

class WaypointControllerNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    const WaypointControllerNodeParams node_params = read_params(p, waypoint_controller_param_table());
    const double rate_hz = node_params.rate_hz;
    params_ = node_params.controller;
    require_valid_ = node_params.require_valid_estimate;
    invalid_estimate_speed_mps_ = node_params.invalid_estimate_speed_mps;
    invalid_estimate_creep_limit_s_ = node_params.invalid_estimate_creep_limit_s;
    estimate_timeout_s_ = node_params.estimate_timeout_s;
    p.validate(params_);  // the body is checked where it is declared (system::check_facts)
    ctx.set_rate_hz(rate_hz, "rate_hz");
    ctx.require_longer_than_period("estimate_timeout_s", estimate_timeout_s_);
    realtime_ = ctx.mode() == TimeMode::kRealtime;
    for (const RobotSpec& robot : ctx.robots()) {
      ControllerParams robot_params = params_;
      robot_params.body = system::robot_body(ctx.scenario(), robot.id);  // the robot it drives
      trackers_.emplace(robot.id, WaypointTracker(robot_params, 1.0 / rate_hz));
    }
    const auto keys = ctx.robot_keys();
    estimates_ = &ctx.subscribe<idl::PoseEstimate>("estimate/pose", Subscription::instances(keys));
    missions_ = &ctx.subscribe<idl::WaypointMission>("mission/waypoints", Subscription::instances(keys));
    cmd_out_ = &ctx.advertise<idl::VelocityCommand>("plant/cmd");
    status_out_ = &ctx.advertise<idl::ControllerStatus>("control/status");
  }

  void on_step(const StepInfo& info) override {
    for (auto& [id, tracker] : trackers_) {
      if (const idl::WaypointMission* mission = missions_->latest(id); mission != nullptr && !tracker.has_mission()) {
        std::vector<Eigen::Vector2d> waypoints;
        for (const idl::Waypoint& w : mission->waypoints()) {
          waypoints.emplace_back(w.x(), w.y());
        }
        tracker.set_mission(std::move(waypoints));  // throws on an empty or non-finite mission
      }
      const idl::PoseEstimate* estimate = estimates_->latest(id);
      idl::VelocityCommand cmd;
      cmd.robot_id(id);
      cmd.mode(idl::VELOCITY);
      idl::ControllerStatus status;
      status.robot_id(id);
      status.epsilon(params_.epsilon_m);
      status.state(state_for(id, tracker, estimate));
      if (status.state() == idl::TRACKING) {
        Eigen::Matrix2d position_covariance;  // row-major 3x3 [x, y, theta] -> its xy block
        position_covariance << estimate->cov()[0], estimate->cov()[1], estimate->cov()[3], estimate->cov()[4];
        const TrackerOutput out = tracker.step(estimate->x(), estimate->y(), estimate->theta(), position_covariance);
        cmd.v(out.command.v);
        cmd.omega(out.command.omega);
        status.waypoint_index(static_cast<std::uint32_t>(out.status.target_index));
        status.waypoints_total(static_cast<std::uint32_t>(tracker.mission().size()));
        status.waypoints_reached(static_cast<std::uint32_t>(out.status.reached_count));
        status.distance_to_waypoint(out.status.distance_to_target_m);
        status.distance_to_final(out.status.distance_to_final_m);
        status.alpha(out.status.alpha_rad);
        status.sigma(out.status.sigma_rad);
        status.done(out.status.done);
        status.switched(out.status.reached_this_step);
        status.switch_distance(out.status.reached_this_step ? out.status.reached_distance_m : 0.0);
        status.state(out.status.done ? idl::DONE : idl::TRACKING);
        creep_started_s_.erase(id);
      } else if (status.state() == idl::ESTIMATE_INVALID && invalid_estimate_speed_mps_ > 0.0 && may_creep(id, info.time_s)) {
        const Command creep = tracker.hold(Command{invalid_estimate_speed_mps_, 0.0});  // until the estimate is valid
        cmd.v(creep.v);
        cmd.omega(creep.omega);
      } else {
        tracker.command_stopped();  // the zero command below: the plant brakes within its own limits
      }
      cmd_out_->publish(cmd);
      status_out_->publish(status);
    }
  }

 private:
  /// Whether robot `id` may still creep at `time_s` (s): within invalid_estimate_creep_limit_s of
  /// the first creeping step since its estimate was last valid. Says once when the limit stops it.
  bool may_creep(std::uint32_t id, double time_s) {
    const double since_s = creep_started_s_.try_emplace(id, time_s).first->second;
    if (invalid_estimate_creep_limit_s_ <= 0.0 || time_s - since_s <= invalid_estimate_creep_limit_s_) {
      return true;
    }
    if (creep_stopped_.insert(id).second) {
      log::warn("waypoint_controller", "robot " + std::to_string(id) + ": no valid pose estimate after " +
                                           std::to_string(time_s - since_s) + " s of creeping "
                                           "(invalid_estimate_creep_limit_s): stopped until the estimate is valid");
    }
    return false;
  }

  /// TRACKING when the tracker may run on `estimate`; otherwise why the command is zero.
  idl::ControlState state_for(std::uint32_t id, const WaypointTracker& tracker, const idl::PoseEstimate* estimate) const {
    if (!tracker.has_mission()) {
      return idl::NO_MISSION;
    }
    if (estimate == nullptr) {
      return idl::NO_ESTIMATE;
    }
    if (realtime_ && !estimates_->fresh(id, estimate_timeout_s_)) {
      return idl::ESTIMATE_STALE;  // judged by this process's receive time, never by the estimator's stamp
    }
    if (!estimate->valid() && require_valid_) {
      return idl::ESTIMATE_INVALID;
    }
    return idl::TRACKING;
  }

  ControllerParams params_;
  bool require_valid_ = true;
  double invalid_estimate_speed_mps_ = 0.0;
  double invalid_estimate_creep_limit_s_ = 60.0;
  std::map<std::uint32_t, double> creep_started_s_;  // robot -> time (s) of its first creeping step
  std::set<std::uint32_t> creep_stopped_;            // robots told once that the creep limit stopped them
  double estimate_timeout_s_ = 0.5;
  bool realtime_ = false;
  std::map<std::uint32_t, WaypointTracker> trackers_;
  Input<idl::PoseEstimate>* estimates_ = nullptr;
  Input<idl::WaypointMission>* missions_ = nullptr;
  Output<idl::VelocityCommand>* cmd_out_ = nullptr;
  Output<idl::ControllerStatus>* status_out_ = nullptr;
};

}  // namespace

std::unique_ptr<Component> make_waypoint_controller_node() { return std::make_unique<WaypointControllerNode>(); }

}  // namespace robodds::waypoint_controller

ROBODDS_REGISTER_COMPONENT(waypoint_controller, "paper 1 way-point tracking: estimate/pose + mission/waypoints -> plant/cmd, control/status",
                           robodds::waypoint_controller::make_waypoint_controller_node,
                           robodds::waypoint_controller::waypoint_controller_param_table);
