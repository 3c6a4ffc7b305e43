// Adapter: RangeRateEstimate / TargetAssignment / PoseEstimate <-> GuidanceLaw <-> VelocityCommand.
#include "components/circumnavigation_controller/node/circumnavigation_controller_node.hpp"

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/estimate_age.hpp"
#include "common/number_text.hpp"
#include "common/model/estimate_gap_hold.hpp"
#include "components/circumnavigation_controller/guidance_law.hpp"
#include "components/circumnavigation_controller/node/circumnavigation_controller_params.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/log.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"
#include "system/robot_facts.hpp"

namespace robodds::circumnavigation_controller {
namespace {

/// Robots whose body (the scenario's shared fact robot_body) cannot do what the law commands: the
/// plant then saturates the commands (the bound still holds; the spacing has less room). Warns.
void warn_about_lower_body_limits(const ComponentContext& ctx, const GuidanceParams& law) {
  for (const RobotSpec& robot : ctx.robots()) {
    const model::RobotBody body = system::robot_body(ctx.scenario(), robot.id);
    const double v = body.limits.max_speed_mps;
    const double w = body.limits.max_turn_rate_radps;
    if ((v > 0.0 && v < max_commanded_speed(law)) || (w > 0.0 && w < law.max_turn_rate_radps)) {
      log::warn(ctx.name(), "robot " + std::to_string(robot.id) + ": its robot_body limits (max_speed_mps " + std::to_string(v) +
                                ", max_turn_rate_radps " + std::to_string(w) + ") are below the law's V_max " +
                                std::to_string(max_commanded_speed(law)) + " m/s / max_turn_rate_radps " +
                                std::to_string(law.max_turn_rate_radps) + " rad/s: the plant saturates the commands");
    }
  }
}

class CircumnavigationControllerNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    const CircumnavigationControllerParams params = read_params(p, circumnavigation_controller_param_table());
    p.validate(params.guidance);
    p.check([&] {
      try {
        params.gap_hold.validate();
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("gap_hold." + std::string(e.what()));  // its keys in this component's table
      }
    });
    ctx.set_rate_hz(params.rate_hz, "rate_hz");
    ctx.require_longer_than_period("estimate_timeout_s", params.estimate_timeout_s);
    ctx.require_longer_than_period("peer_timeout_s", params.peer_timeout_s);
    std::vector<std::uint32_t> team;  // the spacing reads every robot's pose
    for (const RobotSpec& robot : ctx.scenario().robots) {
      team.push_back(robot.id);
    }
    ctx.limits_age_of(to_string(params.observer_topic), "estimate_timeout_s", params.estimate_timeout_s, /*realtime_only=*/true);
    ctx.limits_age_of("estimate/pose", "peer_timeout_s", params.peer_timeout_s, /*realtime_only=*/true, team);
    const system::RangeAccelBound bound = system::range_accel_bound(ctx.scenario());  // the shared fact
    p.check([&] { check_observer_bound(params.guidance, bound.mps2, bound.key); });
    warn_about_lower_body_limits(ctx, params.guidance);
    estimate_timeout_s_ = params.estimate_timeout_s;
    max_accel_mps2_ = params.guidance.max_accel_mps2;
    hold_s_ = params.gap_hold.hold_s;
    peer_timeout_s_ = params.peer_timeout_s;
    dt_s_ = static_cast<double>(ctx.period_steps()) * ctx.step_s();
    step_s_ = ctx.step_s();
    realtime_ = ctx.mode() == TimeMode::kRealtime;
    name_ = ctx.name();
    for (const RobotSpec& robot : ctx.robots()) {
      robots_.emplace(robot.id, Robot{GuidanceLaw(params.guidance), "(not started)", model::Twist{}, control::LateEstimateWatch{},
                                      model::EstimateGapHold(params.gap_hold)});
    }
    std::vector<std::uint64_t> all_robots;
    for (const RobotSpec& robot : ctx.scenario().robots) {
      all_robots.push_back(robot.id);
      team_[robot.id] = TeamMate{};
    }
    observer_ = &ctx.subscribe<idl::RangeRateEstimate>(to_string(params.observer_topic),
                                                        Subscription::robot_streams(ctx.robot_keys()));
    missions_ = &ctx.subscribe<idl::TargetAssignment>("mission/target", Subscription::instances(all_robots));
    poses_ = &ctx.subscribe<idl::PoseEstimate>("estimate/pose", Subscription::instances(all_robots));
    cmd_out_ = &ctx.advertise<idl::VelocityCommand>("plant/cmd");
  }

  void on_step(const StepInfo&) override {
    // Read every robot's newest task and pose first (latest() consumes what is readable).
    for (auto& [id, team_mate] : team_) {
      team_mate.task = missions_->latest(id);
      team_mate.pose = poses_->latest(id);
    }
    for (auto& [id, robot] : robots_) {
      idl::VelocityCommand cmd;
      cmd.robot_id(id);
      cmd.mode(idl::VELOCITY);
      const idl::TargetAssignment* task = team_.at(id).task;
      const idl::RangeRateEstimate* estimate = observer_->latest_of_robot(id);
      const ZeroReason why = zero_reason(id, task, estimate);
      std::string state;  // for the log: "" steering, else why not
      if (why.text.empty()) {
        // A late estimate (real time: frozen, not yet stale) is no news: the law would ramp on it
        // (issue 24, finding 5), so the last command is held until it is fresh or stale.
        if (!estimate_is_late(id, robot, *estimate)) {
          robot.last_command = robot.law.step(estimate->range(), estimate->range_rate(), task->desired_radius(),
                                              gaps_of(id, *task), dt_s_);
        }
        robot.hold.steered(robot.last_command);
      } else if (const std::optional<model::Twist> held = why.gap ? robot.hold.gap(dt_s_, max_accel_mps2_) : std::nullopt) {
        // Issue 27: a brief gap of the estimate (a restart window, a target switch) does not stop
        // a robot that was steering: its last curvature, slowing, for at most gap_hold.hold_s.
        robot.last_command = *held;
        robot.law.continue_from(held->v);
        state = "holding its last curvature at reduced speed (at most " + shortest_text(hold_s_) + " s): " + why.text;
      } else {
        robot.law.reset();  // the robot stops; it starts again from rest
        robot.hold.stopped();
        robot.last_command = model::Twist{};
        state = "zero command: " + why.text;
      }
      cmd.v(robot.last_command.v);
      cmd.omega(robot.last_command.omega);
      report(id, robot, state);
      cmd_out_->publish(cmd);
    }
  }

 private:
  struct Robot {
    GuidanceLaw law;
    std::string last_reason = "(not started)";  // what the last command was ("" = steering), for the log
    model::Twist last_command;                   // m/s, rad/s: what was last commanded
    control::LateEstimateWatch late;             // of its observer estimates
    model::EstimateGapHold hold;                        // through a brief gap of the estimate (issue 27)
  };

  /// Why a robot's law may not run: "" it may; `gap` when the estimate is only briefly unusable
  /// (its restart window, a target switch the observer has not followed yet), which a steering
  /// robot may ride through (EstimateGapHold). A stale estimate (real time) is no gap: it stops.
  struct ZeroReason {
    std::string text;
    bool gap = false;
  };

  /// Real time: the observer's estimate is older than two of its periods (by this process's
  /// receive time) but not stale (common/estimate_age.hpp). Says once per robot when it first is.
  bool estimate_is_late(std::uint32_t id, Robot& robot, const idl::RangeRateEstimate& estimate) const {
    if (!realtime_) {
      return false;  // lockstep: every estimate is the one of its step
    }
    std::string warning;
    const bool late = robot.late.late(observer_->age_s(id).value_or(estimate_timeout_s_), estimate.header().step(),
                                      estimate.header().next_step(), step_s_, estimate_timeout_s_, warning);
    if (!warning.empty()) {
      log::warn(name_, "robot " + std::to_string(id) + ": estimate on " + observer_->topic() + " " + warning);
    }
    return late;
  }

  /// Why robot `id` must not steer, or "" when the law may run.
  ZeroReason zero_reason(std::uint32_t id, const idl::TargetAssignment* task, const idl::RangeRateEstimate* estimate) const {
    if (task == nullptr) {
      return {"no task on mission/target yet"};
    }
    if (!task->active()) {
      return {"no target (LEAVE on mission/target)"};
    }
    if (!(task->desired_radius() > 0.0)) {
      return {"desired_radius: must be > 0 (got " + std::to_string(task->desired_radius()) + ") for target " +
              std::to_string(task->target_id())};
    }
    if (estimate == nullptr) {
      return {"no estimate on " + observer_->topic() + " yet"};
    }
    if (estimate->target_id() != task->target_id()) {
      return {"the estimate on " + observer_->topic() + " is of target " + std::to_string(estimate->target_id()) +
                  ", the task's is " + std::to_string(task->target_id()),
              true};
    }
    if (realtime_ && !observer_->fresh(id, estimate_timeout_s_)) {
      // The receive time of this process, not the stamp. Not a gap to ride through: a silent
      // observer may be dead (it was already held while late, up to estimate_timeout_s).
      return {"the estimate on " + observer_->topic() + " is older than estimate_timeout_s " +
              std::to_string(estimate_timeout_s_) + " s"};
    }
    if (!estimate->valid()) {
      return {"the estimate on " + observer_->topic() + " is not valid (observer restart window)", true};
    }
    return {};
  }

  /// The gaps of robot `id` among the robots with the same active target and a known (in real
  /// time: fresh) pose; alone (no spacing) while its own pose is unknown.
  Gaps gaps_of(std::uint32_t id, const idl::TargetAssignment& task) const {
    auto bearing_of = [&](std::uint32_t robot) {
      const idl::PoseEstimate* pose = team_.at(robot).pose;
      return TeamBearing{robot, bearing_from_target(pose->x(), pose->y(), task.target_x(), task.target_y())};
    };
    if (!pose_usable(id)) {
      return Gaps{};
    }
    std::vector<TeamBearing> peers;
    for (const auto& [peer, team_mate] : team_) {
      const idl::TargetAssignment* peer_task = team_mate.task;
      if (peer != id && peer_task != nullptr && peer_task->active() && peer_task->target_id() == task.target_id() &&
          pose_usable(peer)) {
        peers.push_back(bearing_of(peer));
      }
    }
    return formation_gaps(bearing_of(id), peers);
  }

  bool pose_usable(std::uint32_t robot) const {
    return team_.at(robot).pose != nullptr && (!realtime_ || poses_->fresh(robot, peer_timeout_s_));
  }

  /// Says once why a robot's commands are zero (or held), and once when it steers again.
  void report(std::uint32_t id, Robot& robot, const std::string& state) {
    if (state == robot.last_reason) {
      return;
    }
    if (state.empty()) {
      log::info(name_, "robot " + std::to_string(id) + ": steering (" + observer_->topic() + ")");
    } else {
      log::info(name_, "robot " + std::to_string(id) + ": " + state);
    }
    robot.last_reason = state;
  }

  double estimate_timeout_s_ = 0.5;
  double max_accel_mps2_ = 0.5;  // the law's: how fast a held robot slows
  double hold_s_ = 1.0;          // gap_hold.hold_s
  double peer_timeout_s_ = 1.0;
  double dt_s_ = 0.02;
  double step_s_ = 0.01;
  bool realtime_ = false;
  std::string name_;
  std::map<std::uint32_t, Robot> robots_;
  /// Every scenario robot's newest task and pose, read at the start of each step (pointers into
  /// the inputs, valid for the step).
  struct TeamMate {
    const idl::TargetAssignment* task = nullptr;
    const idl::PoseEstimate* pose = nullptr;
  };
  std::map<std::uint32_t, TeamMate> team_;
  Input<idl::RangeRateEstimate>* observer_ = nullptr;
  Input<idl::TargetAssignment>* missions_ = nullptr;
  Input<idl::PoseEstimate>* poses_ = nullptr;
  Output<idl::VelocityCommand>* cmd_out_ = nullptr;
};

}  // namespace

std::unique_ptr<Component> make_circumnavigation_controller_node() {
  return std::make_unique<CircumnavigationControllerNode>();
}

}  // namespace robodds::circumnavigation_controller

ROBODDS_REGISTER_COMPONENT(circumnavigation_controller,
                           "paper 2 circumnavigation guidance: observer/range_rate + mission/target + estimate/pose -> plant/cmd",
                           robodds::circumnavigation_controller::make_circumnavigation_controller_node,
                           robodds::circumnavigation_controller::circumnavigation_controller_param_table);
