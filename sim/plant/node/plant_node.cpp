// Adapter: VelocityCommand -> Twist -> diff_drive -> RobotState. No maths beyond unit plumbing.
#include "sim/plant/node/plant_node.hpp"

#include <cmath>
#include <map>

#include "robodds/idl/robodds.h"
#include "runtime/param_table_reader.hpp"
#include "sim/plant/node/plant_params.hpp"
#include "sim/plant/diff_drive.hpp"
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
      robots_[robot.id] = Robot{Pose2{robot.x, robot.y, robot.theta}, Twist{}};
    }
    InputOptions cmd_options;
    cmd_options.expected = ctx.robot_keys();
    cmd_options.delay_steps = 1;  // closes the loop: integrate the command of the previous step
    commands_ = &ctx.subscribe<idl::VelocityCommand>("plant/cmd", cmd_options);
    state_out_ = &ctx.advertise<idl::RobotState>("plant/state");
    mode_ = ctx.mode();
  }

  void on_step(const StepInfo& info) override {
    for (auto& [id, robot] : robots_) {
      const Twist twist = command_for(id, info);
      if (info.dt_s > 0.0) {
        robot.pose = integrate_exact(robot.pose, twist, info.dt_s);
      }
      robot.applied = info.dt_s > 0.0 ? twist : Twist{};
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
    Pose2 pose;
    Twist applied;
  };

  Twist command_for(std::uint32_t id, const StepInfo& info) {
    const idl::VelocityCommand* cmd = commands_->latest(id);
    if (cmd == nullptr) {
      return Twist{};  // no command yet: stand still
    }
    if (mode_ == TimeMode::kRealtime) {
      const double age_s = static_cast<double>(info.stamp_ns - cmd->header().stamp_ns()) * 1e-9;
      if (age_s > params_.command_timeout_s) {
        return Twist{};  // stale command: safe stop
      }
    }
    const Twist requested = cmd->mode() == idl::WHEEL_SPEEDS
                                ? twist_from_wheel_speeds(cmd->v_left(), cmd->v_right(), params_.wheel_base_m)
                                : Twist{cmd->v(), cmd->omega()};
    if (!std::isfinite(requested.v) || !std::isfinite(requested.omega)) {
      return Twist{};  // never integrate a non-finite command
    }
    return saturate(requested, params_.limits);
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
