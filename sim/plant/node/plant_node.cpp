// Adapter: VelocityCommand -> Twist -> diff-drive kinematics (common/model) -> RobotState. No maths beyond unit plumbing.
#include "sim/plant/node/plant_node.hpp"

#include <cmath>
#include <map>

#include "common/model/diff_drive_kinematics.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/param_table_reader.hpp"
#include "runtime/registry.hpp"
#include "sim/plant/node/plant_node_params.hpp"
#include "sim/plant/plant_params.hpp"

namespace robodds::plant {
namespace {

class PlantNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    const PlantNodeParams node_params = read_params(p, plant_param_table());
    params_ = node_params.plant;
    const double rate_hz = node_params.rate_hz;
    p.validate(params_);
    ctx.set_rate_hz(rate_hz, "rate_hz");
    for (const RobotSpec& robot : ctx.robots()) {
      robots_[robot.id] = Robot{model::Pose2{robot.x, robot.y, robot.theta}, model::Twist{}};
    }
    // delayed(1) closes the loop: integrate the command of the previous step.
    commands_ = &ctx.subscribe<idl::VelocityCommand>("plant/cmd", Subscription::instances(ctx.robot_keys()).delayed(1));
    state_out_ = &ctx.advertise<idl::RobotState>("plant/state");
    mode_ = ctx.mode();
  }

  void on_step(const StepInfo& info) override {
    for (auto& [id, robot] : robots_) {
      const model::Twist twist = command_for(id, info);
      if (info.dt_s > 0.0) {
        robot.pose = model::integrate_exact(robot.pose, twist, info.dt_s);
      }
      robot.applied = info.dt_s > 0.0 ? twist : model::Twist{};
      idl::RobotState state;
      state.robot_id(id);
      state.x(robot.pose.x);
      state.y(robot.pose.y);
      state.theta(robot.pose.theta);
      state.v(robot.applied.v);
      state.omega(robot.applied.omega);
      state_out_->publish(state);
    }
  }

 private:
  struct Robot {
    model::Pose2 pose;
    model::Twist applied;
  };

  model::Twist command_for(std::uint32_t id, const StepInfo& info) {
    const idl::VelocityCommand* cmd = commands_->latest(id);
    if (cmd == nullptr) {
      return model::Twist{};  // no command yet: stand still
    }
    if (mode_ == TimeMode::kRealtime) {
      const double age_s = static_cast<double>(info.stamp_ns - cmd->header().stamp_ns()) * 1e-9;
      if (age_s > params_.command_timeout_s) {
        return model::Twist{};  // stale command: safe stop
      }
    }
    const model::Twist requested = cmd->mode() == idl::WHEEL_SPEEDS
                                       ? model::twist_from_wheel_speeds(cmd->v_left(), cmd->v_right(), params_.wheel_base_m)
                                       : model::Twist{cmd->v(), cmd->omega()};
    if (!std::isfinite(requested.v) || !std::isfinite(requested.omega)) {
      return model::Twist{};  // never integrate a non-finite command
    }
    return model::saturate(requested, params_.limits);
  }

  PlantParams params_;
  std::map<std::uint32_t, Robot> robots_;
  Input<idl::VelocityCommand>* commands_ = nullptr;
  Output<idl::RobotState>* state_out_ = nullptr;
  TimeMode mode_ = TimeMode::kLockstep;
};

}  // namespace

std::unique_ptr<Component> make_plant_node() { return std::make_unique<PlantNode>(); }

}  // namespace robodds::plant

ROBODDS_REGISTER_COMPONENT(plant, "differential-drive plant (paper 1 eq. 1): plant/cmd -> plant/state",
                           robodds::plant::make_plant_node,
                           robodds::plant::plant_param_table);
