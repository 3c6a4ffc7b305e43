// Adapter: PoseEstimate/WaypointMission <-> WaypointTracker <-> VelocityCommand/ControllerStatus.
#include "components/waypoint_controller/node/waypoint_controller_node.hpp"

#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include "components/waypoint_controller/creep_budget.hpp"
#include "common/estimate_age.hpp"
#include "common/model/estimate_gap_hold.hpp"
#include "common/number_text.hpp"
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
    const CreepLimits creep_limits{node_params.invalid_estimate_creep_max_m, node_params.invalid_estimate_creep_limit_s,
                                   node_params.invalid_estimate_creep_restarts, node_params.invalid_estimate_creep_extensions,
                                   node_params.invalid_estimate_creep_progress, node_params.invalid_estimate_creep_relearns,
                                   node_params.invalid_estimate_relearn_max_position_std_m};
    estimate_timeout_s_ = node_params.estimate_timeout_s;
    p.validate(params_);  // the body is checked where it is declared (system::check_facts)
    p.check([&] {
      try {
        node_params.gap_hold.validate();
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("gap_hold." + std::string(e.what()));  // its keys in this component's table
      }
    });
    ctx.set_rate_hz(rate_hz, "rate_hz");
    ctx.require_longer_than_period("estimate_timeout_s", estimate_timeout_s_);
    ctx.limits_age_of("estimate/pose", "estimate_timeout_s", estimate_timeout_s_, /*realtime_only=*/true);
    realtime_ = ctx.mode() == TimeMode::kRealtime;
    period_s_ = 1.0 / rate_hz;
    step_s_ = ctx.step_s();
    for (const RobotSpec& robot : ctx.robots()) {
      ControllerParams robot_params = params_;
      robot_params.body = system::robot_body(ctx.scenario(), robot.id);  // the robot it drives
      robots_.emplace(robot.id, Robot{WaypointTracker(robot_params, period_s_), CreepBudget(creep_limits), TrackerStatus{},
                                      CreepVerdict::kAllowed, control::LateEstimateWatch{}, 0,
                                      model::EstimateGapHold(node_params.gap_hold)});
    }
    const auto keys = ctx.robot_keys();
    estimates_ = &ctx.subscribe<idl::PoseEstimate>("estimate/pose", Subscription::instances(keys));
    missions_ = &ctx.subscribe<idl::WaypointMission>("mission/waypoints", Subscription::instances(keys));
    cmd_out_ = &ctx.advertise<idl::VelocityCommand>("plant/cmd");
    status_out_ = &ctx.advertise<idl::ControllerStatus>("control/status");
  }

  void on_step(const StepInfo& info) override {
    for (auto& [id, robot] : robots_) {
      WaypointTracker& tracker = robot.tracker;
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
      if (estimate != nullptr && status.state() != idl::ESTIMATE_STALE) {
        note_restarts(id, robot, *estimate, info.time_s);
        if (estimate->valid()) {
          robot.creep.estimate_was_valid();  // from now on the robot never drives without one
        }
      }
      if (status.state() == idl::TRACKING && estimate_is_late(id, robot, *estimate)) {
        const Command held = tracker.last_command();  // a frozen pose is no news: no higher command
        cmd.v(held.v);
        cmd.omega(held.omega);
        set_tracking(status, robot.last_tracked, false);
        steered(robot, held);
      } else if (status.state() == idl::TRACKING) {
        Eigen::Matrix2d position_covariance;  // row-major 3x3 [x, y, theta] -> its xy block
        position_covariance << estimate->cov()[0], estimate->cov()[1], estimate->cov()[3], estimate->cov()[4];
        const TrackerOutput out = tracker.step(estimate->x(), estimate->y(), estimate->theta(), position_covariance);
        cmd.v(out.command.v);
        cmd.omega(out.command.omega);
        robot.last_tracked = out.status;
        if (out.status.reached_this_step) {
          robot.creep.waypoint_reached();  // the relearns in a row start again
        }
        set_tracking(status, out.status, out.status.reached_this_step);
        steered(robot, out.command);
      } else if (status.state() == idl::ESTIMATE_INVALID) {
        // Issue 27: a robot that was tracking and is moving rides through a brief invalid estimate
        // on the arc of its last command, slowing, for at most gap_hold.hold_s (never once the
        // mission is done). Else, or once the hold ran out: creep ahead until the first valid
        // estimate (within its budget), else stop: v = omega = 0, reached within the robot's
        // acceleration limits like the stop at the mission's end (the plant would brake no faster
        // on an instant zero, and a one-step flicker of `valid` does not restart the ramp from
        // rest while the robot is still at speed).
        // Not an estimate whose producer says its own inputs went stale (real time: the sensors may
        // be dead): that stops the robot as a stale estimate does (issue 24).
        const bool may_hold = !tracker.done() && !estimate->inputs_stale();
        // A held robot slows within its body's max_accel_mps2 (0 = no limit: the reduced speed at once).
        const double max_decel_mps2 = tracker.params().body.actuator.max_accel_mps2;
        const std::optional<model::Twist> held = may_hold ? robot.hold.gap(period_s_, max_decel_mps2) : std::nullopt;
        if (!may_hold) {
          robot.hold.stopped();
        }
        report_hold(id, robot, held.has_value(), info.time_s);
        if (held) {
          const Command out = tracker.hold(Command{held->v, held->omega});  // within the wheel and acceleration limits
          cmd.v(out.v);
          cmd.omega(out.omega);
        } else {
          robot.creep.observe_heading_std(std::sqrt(std::max(0.0, estimate->cov()[8])));
          robot.creep.observe_position_std(std::sqrt(std::max(0.0, estimate->cov()[0] + estimate->cov()[4])),
                                           estimate->inputs_stale());
          const bool creeping = invalid_estimate_speed_mps_ > 0.0 && may_creep(id, robot, info.time_s);
          const Command out = tracker.hold(creeping ? Command{invalid_estimate_speed_mps_, 0.0} : Command{});
          if (creeping) {
            robot.creep.crept(out.v, period_s_);
          }
          cmd.v(out.v);
          cmd.omega(out.omega);
        }
      } else {
        // No mission, no estimate, or (real time) a stale one: its producer may be dead. Never held.
        robot.hold.stopped();
        tracker.command_stopped();  // the zero command below: the plant brakes within its own limits
      }
      set_progress(status, tracker);  // the mission's progress in every state (issue 24, finding 8)
      cmd_out_->publish(cmd);
      status_out_->publish(status);
    }
  }

 private:
  struct Robot {
    WaypointTracker tracker;
    CreepBudget creep;
    TrackerStatus last_tracked;                  // of its last tracking step, repeated while the estimate is late
    CreepVerdict told = CreepVerdict::kAllowed;  // the last refusal logged
    control::LateEstimateWatch late;             // of its pose estimates
    std::uint32_t restarts_seen = 0;             // the estimator's restart count last seen
    model::EstimateGapHold hold;                 // through a brief invalid estimate (issue 27)
    bool said_hold = false;                      // a hold was logged (once per run)
    bool said_expiry = false;                    // a hold that ran out was logged (once per run)
  };

  /// The robot was driven by the tracker's `command` at this step: a following invalid estimate
  /// may be held on its arc, unless the mission is done (the robot stops there for good).
  static void steered(Robot& robot, const Command& command) {
    if (robot.tracker.done()) {
      robot.hold.stopped();
    } else {
      robot.hold.steered(model::Twist{command.v, command.omega});
    }
  }

  /// Says the first time a robot is held, and the first time a hold runs out (not again: `valid`
  /// may flicker all run long).
  static void report_hold(std::uint32_t id, Robot& robot, bool holding, double time_s) {
    const std::string robot_text = "robot " + std::to_string(id) + ": ";
    if (holding && !robot.said_hold) {
      log::info("waypoint_controller", robot_text + "the estimate is not valid at " + std::to_string(time_s) +
                                           " s: holding the arc of the last command at reduced speed for at most "
                                           "gap_hold.hold_s " + shortest_text(robot.hold.params().hold_s) +
                                           " s (said once)");
      robot.said_hold = true;
    } else if (!holding && robot.hold.gap_s() > robot.hold.params().hold_s && robot.said_hold && !robot.said_expiry) {
      log::info("waypoint_controller", robot_text + "still not valid after gap_hold.hold_s at " + std::to_string(time_s) +
                                           " s: the hold ended (said once)");
      robot.said_expiry = true;
    }
  }

  /// The estimator restarted (its count rose since the last estimate seen): a new creep budget
  /// while the run's allowance lasts (creep_budget.hpp). Says which, once per restart.
  static void note_restarts(std::uint32_t id, Robot& robot, const idl::PoseEstimate& estimate, double time_s) {
    if (estimate.restarts() <= robot.restarts_seen) {
      return;
    }
    robot.restarts_seen = estimate.restarts();
    const bool granted = robot.creep.estimator_restarted();
    log::warn("waypoint_controller", "robot " + std::to_string(id) + ": the estimator restarted at " + std::to_string(time_s) +
                                         " s (restart " + std::to_string(estimate.restarts()) + "): " +
                                         (granted ? "a new creep budget until its next valid estimate"
                                                  : "invalid_estimate_creep_restarts used up: no creeping"));
    robot.told = CreepVerdict::kAllowed;  // a refusal after this restart is said again
  }

  /// Way-point index, total, reached and done from the tracker: true in every state.
  static void set_progress(idl::ControllerStatus& status, const WaypointTracker& tracker) {
    status.waypoint_index(static_cast<std::uint32_t>(tracker.target_index()));
    status.waypoints_total(static_cast<std::uint32_t>(tracker.mission().size()));
    status.waypoints_reached(static_cast<std::uint32_t>(tracker.reached_count()));
    status.done(tracker.done());
  }

  /// The tracking fields of a step that tracked on (or, late, held) the estimate.
  static void set_tracking(idl::ControllerStatus& status, const TrackerStatus& tracked, bool switched) {
    status.distance_to_waypoint(tracked.distance_to_target_m);
    status.distance_to_final(tracked.distance_to_final_m);
    status.alpha(tracked.alpha_rad);
    status.sigma(tracked.sigma_rad);
    status.switched(switched);
    status.switch_distance(switched ? tracked.reached_distance_m : 0.0);
    status.state(tracked.done ? idl::DONE : idl::TRACKING);
  }

  /// Real time: the estimate is older than two of its producer's periods (by this process's
  /// receive time) but not stale. Says once per robot when that first happens.
  bool estimate_is_late(std::uint32_t id, Robot& robot, const idl::PoseEstimate& estimate) const {
    if (!realtime_) {
      return false;  // lockstep: every estimate is the one of its step
    }
    std::string warning;
    const bool late = robot.late.late(estimates_->age_s(id).value_or(estimate_timeout_s_), estimate.header().step(),
                                      estimate.header().next_step(), step_s_, estimate_timeout_s_, warning);
    if (!warning.empty()) {
      log::warn("waypoint_controller", "robot " + std::to_string(id) + ": estimate " + warning);
    }
    return late;
  }

  /// Whether robot `id` may creep at `time_s` (s) (creep_budget.hpp). Says once why it may not.
  static bool may_creep(std::uint32_t id, Robot& robot, double time_s) {
    const int extensions = robot.creep.extensions();
    const int relearns = robot.creep.relearns();
    const CreepVerdict verdict = robot.creep.check(time_s, robot.tracker.done());
    if (robot.creep.relearns() > relearns) {
      log::info("waypoint_controller", "robot " + std::to_string(id) + ": the estimate, valid before, is not at " +
                                           std::to_string(time_s) + " s with its position known: creeping to learn the "
                                           "heading again (relearn " + std::to_string(robot.creep.relearns()) +
                                           " since the last way-point)");
      robot.told = CreepVerdict::kAllowed;  // a refusal after this relearn is said again
    }
    if (robot.creep.extensions() > extensions) {
      log::info("waypoint_controller", "robot " + std::to_string(id) + ": creep budget extended (" +
                                           std::to_string(robot.creep.extensions()) + ") at " + std::to_string(time_s) +
                                           " s: the estimate's heading std is still falling");
    }
    if (verdict != CreepVerdict::kAllowed && verdict != robot.told) {
      log::warn("waypoint_controller", "robot " + std::to_string(id) + ": no valid pose estimate at " +
                                           std::to_string(time_s) + " s: " + describe(verdict));
    }
    robot.told = verdict;
    return verdict == CreepVerdict::kAllowed;
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
  double estimate_timeout_s_ = 0.5;
  double period_s_ = 0.01;  // s, the control period (1 / rate_hz)
  double step_s_ = 0.01;    // s, the scenario's step (header steps -> seconds)
  bool realtime_ = false;
  std::map<std::uint32_t, Robot> robots_;
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
