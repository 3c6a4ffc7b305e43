// Adapter: VelocityCommand -> Twist -> diff-drive kinematics (common/model) -> RobotState. No maths beyond unit plumbing.
#include "sim/plant/node/plant_node.hpp"

#include <cmath>
#include <cstdint>
#include <map>
#include <optional>

#include "common/model/actuator.hpp"
#include "common/model/diff_drive_kinematics.hpp"
#include "common/model/robot_body.hpp"
#include "sim/plant/disturbance.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"
#include "sim/plant/node/plant_params.hpp"
#include "sim/plant/plant_model_params.hpp"
#include "system/robot_facts.hpp"

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
    ctx.require_longer_than_period("command_timeout_s", params_.command_timeout_s);
    ctx.limits_age_of("plant/cmd", "command_timeout_s", params_.command_timeout_s, /*realtime_only=*/true);
    for (const RobotSpec& robot : ctx.robots()) {
      robots_[robot.id] = Robot{model::Pose2{robot.x, robot.y, robot.theta}, model::Twist{}, false,
                                system::robot_body(ctx.scenario(), robot.id)};
    }
    // delayed(1) closes the loop: integrate the command of the previous step.
    commands_ = &ctx.subscribe<idl::VelocityCommand>("plant/cmd", Subscription::instances(ctx.robot_keys()).delayed(1));
    state_out_ = &ctx.advertise<idl::RobotState>("plant/state");
    mode_ = ctx.mode();
  }

  void on_step(const StepInfo& info) override {
    for (auto& [id, robot] : robots_) {
      // What the wheels can do (|v|, |omega| and wheel-speed limits), then how fast they get there.
      const Target target = command_for(id, robot.body, info.stamp_ns);
      const bool moves = info.dt_s > 0.0;  // not on the first step
      // A command is reached within the acceleration limits; a safe stop (no command yet, a stale
      // or non-finite one) is immediate, as a motor driver's watchdog stops the wheels.
      const model::Twist twist = moves && target.step
                                     ? model::limit_acceleration(target.twist, robot.applied, info.dt_s, robot.body.actuator)
                                     : model::Twist{};
      if (moves && target.step && (twist.v != target.twist.v || twist.omega != target.twist.omega)) {
        count_once(counted_acceleration_, id, *target.step, "acceleration_limited");
      }
      if (moves) {
        robot.pose = model::integrate_exact(robot.pose, twist, info.dt_s);
      }
      if (params_.disturbance.due(info.time_s, robot.disturbed)) {
        robot.pose = apply_disturbance(robot.pose, params_.disturbance);  // kidnapped: no motion, v and omega unchanged
        robot.disturbed = true;
      }
      robot.applied = twist;
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
    bool disturbed = false;  // the pose jump (PlantParams::disturbance) was applied
    model::RobotBody body;   // the scenario's shared fact robot_body for this robot
  };

  /// How long `cmd` was held up on its way, beyond the fastest command of this robot so far.
  /// Its delay (receive wall time - sender's stamp) includes the two clocks' offset; the smallest
  /// delay seen is that offset plus the fastest transit, so the difference is the hold-up,
  /// whatever the offset. A command queued in the sender's kernel while a cable was cut is
  /// delivered when the link returns, seconds old but just received
  /// (integration.netns_link_cut); the receive age alone would call it fresh.
  double held_up_s(std::uint32_t id, const idl::VelocityCommand& cmd, std::int64_t now_wall_ns, double age_s) {
    const std::int64_t received_wall_ns = now_wall_ns - static_cast<std::int64_t>(std::llround(age_s * 1e9));
    const std::int64_t delay_ns = received_wall_ns - cmd.header().stamp_ns();
    auto [it, first] = fastest_delay_ns_.try_emplace(id, delay_ns);
    if (!first && delay_ns < it->second) {
      it->second = delay_ns;
    }
    return static_cast<double>(delay_ns - it->second) * 1e-9;
  }

  /// The twist the plant steers towards: the command within the limits, or a stop.
  struct Target {
    model::Twist twist;
    std::optional<std::uint64_t> step;  // the step of the command it comes from (none: a stop)
  };

  /// Counts `reason` once per command (by its step), not per step it is applied.
  void count_once(std::map<std::uint32_t, std::uint64_t>& counted, std::uint32_t id, std::uint64_t step,
                  const char* reason) {
    const auto [it, first] = counted.try_emplace(id, step);
    if (first || it->second != step) {
      it->second = step;
      commands_->count_adjusted(reason);
    }
  }

  Target command_for(std::uint32_t id, const model::RobotBody& body, std::int64_t now_wall_ns) {
    const idl::VelocityCommand* cmd = commands_->latest(id);
    if (cmd == nullptr) {
      return {};  // no command yet: stand still
    }
    if (mode_ == TimeMode::kRealtime) {
      // Age by this process's receive time (monotonic), never by the sender's stamp: a stamp in
      // the future would otherwise keep a command alive forever.
      const std::optional<double> age_s = commands_->age_s(id);
      if (!age_s || *age_s + held_up_s(id, *cmd, now_wall_ns, *age_s) > params_.command_timeout_s) {
        return {};  // stale command: safe stop
      }
    }
    // The input has refused commands beyond the gross bounds (runtime/io/sample_checks.hpp) and
    // bad modes; what is left is saturated to this robot's limits (its body) and counted.
    const model::Twist requested = cmd->mode() == idl::WHEEL_SPEEDS
                                       ? model::twist_from_wheel_speeds(cmd->v_left(), cmd->v_right(), body.wheel_base_m)
                                       : model::Twist{cmd->v(), cmd->omega()};
    if (!std::isfinite(requested.v) || !std::isfinite(requested.omega)) {
      return {};  // never integrate a non-finite command
    }
    const model::Twist applied = model::clamp_wheel_speeds(model::saturate(requested, body.limits), body.wheel_base_m,
                                                           body.actuator.max_wheel_speed_mps);
    if (applied.v != requested.v || applied.omega != requested.omega) {
      count_once(counted_saturation_, id, cmd->header().step(), "saturated");
    }
    return Target{applied, cmd->header().step()};
  }

  std::map<std::uint32_t, std::uint64_t> counted_saturation_;  // robot -> step of the last command counted
  std::map<std::uint32_t, std::uint64_t> counted_acceleration_;  // the same for "acceleration_limited"
  std::map<std::uint32_t, std::int64_t> fastest_delay_ns_;  // robot -> smallest receive wall time - stamp (real time)

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
