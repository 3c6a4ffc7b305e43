// Adapter: PoseEstimate <-> RouteFollower <-> VelocityCommand.
#include "components/route_follower/node/route_follower_node.hpp"

#include <map>
#include <string>

#include "components/route_follower/node/route_follower_params.hpp"
#include "components/route_follower/route_follower.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/log.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"

namespace robodds::route_follower {
namespace {

class RouteFollowerNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    const RouteFollowerNodeParams params = read_params(p, route_follower_param_table());
    p.validate(params.route);
    ctx.set_rate_hz(params.rate_hz, "rate_hz");
    ctx.require_longer_than_period("estimate_timeout_s", params.estimate_timeout_s);
    ctx.limits_age_of("estimate/pose", "estimate_timeout_s", params.estimate_timeout_s, /*realtime_only=*/true);
    estimate_timeout_s_ = params.estimate_timeout_s;
    dt_s_ = static_cast<double>(ctx.period_steps()) * ctx.step_s();
    realtime_ = ctx.mode() == TimeMode::kRealtime;
    name_ = ctx.name();
    for (const RobotSpec& robot : ctx.robots()) {
      robots_.emplace(robot.id, Robot{RouteFollower(params.route), "(not started)"});
    }
    estimates_ = &ctx.subscribe<idl::PoseEstimate>("estimate/pose", Subscription::instances(ctx.robot_keys()));
    cmd_out_ = &ctx.advertise<idl::VelocityCommand>("plant/cmd");
  }

  void on_step(const StepInfo&) override {
    for (auto& [id, robot] : robots_) {
      const idl::PoseEstimate* estimate = estimates_->latest(id);
      idl::VelocityCommand cmd;
      cmd.robot_id(id);
      cmd.mode(idl::VELOCITY);
      const std::string why_zero = zero_reason(id, estimate);
      if (why_zero.empty()) {
        const FollowerOutput out = robot.follower.step(model::Pose2{estimate->x(), estimate->y(), estimate->theta()}, dt_s_);
        cmd.v(out.twist.v);
        cmd.omega(out.twist.omega);
      }
      report(id, robot, why_zero);
      cmd_out_->publish(cmd);
    }
  }

 private:
  struct Robot {
    RouteFollower follower;
    std::string last_reason;  // why the last command was zero ("" = following)
  };

  /// Why robot `id` must get a zero command, or "" when the follower may run.
  std::string zero_reason(std::uint32_t id, const idl::PoseEstimate* estimate) const {
    if (estimate == nullptr) {
      return "no estimate on estimate/pose yet";
    }
    if (realtime_ && !estimates_->fresh(id, estimate_timeout_s_)) {
      // The receive time of this process, never the estimator's stamp.
      return "the estimate on estimate/pose is older than estimate_timeout_s " + std::to_string(estimate_timeout_s_) + " s";
    }
    if (!estimate->valid()) {
      return "the estimate on estimate/pose is not valid";
    }
    return "";
  }

  /// Says once why a robot's commands are zero, and once when it follows its route again.
  void report(std::uint32_t id, Robot& robot, const std::string& why_zero) {
    if (why_zero == robot.last_reason) {
      return;
    }
    if (why_zero.empty()) {
      log::info(name_, "robot " + std::to_string(id) + ": following its route");
    } else {
      log::info(name_, "robot " + std::to_string(id) + ": zero command: " + why_zero);
    }
    robot.last_reason = why_zero;
  }

  double estimate_timeout_s_ = 0.5;
  double dt_s_ = 0.02;
  bool realtime_ = false;
  std::string name_;
  std::map<std::uint32_t, Robot> robots_;
  Input<idl::PoseEstimate>* estimates_ = nullptr;
  Output<idl::VelocityCommand>* cmd_out_ = nullptr;
};

}  // namespace

std::unique_ptr<Component> make_route_follower_node() { return std::make_unique<RouteFollowerNode>(); }

}  // namespace robodds::route_follower

ROBODDS_REGISTER_COMPONENT(route_follower,
                           "route follower (paper 3): estimate/pose -> plant/cmd, turn in place then drive each segment",
                           robodds::route_follower::make_route_follower_node, robodds::route_follower::route_follower_param_table);
