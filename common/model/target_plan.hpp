#pragma once
// Paper 2's mission: targets to circle and the events that (re)assign robots to them over time.
// A scenario declares it (`targets:` and `events:`, parsed by system/mission_plan.hpp); the target_mission
// component publishes each robot's task on mission/target, and every other component learns its
// task from that topic. Pure: SI units, world frame, time in s.

#include <cstdint>
#include <map>
#include <vector>

namespace robodds::model {

struct Target {
  std::uint32_t id = 0;
  double x = 0.0;         // m, world
  double y = 0.0;         // m, world
  double radius_m = 0.0;  // m, > 0: radius of the circle the team keeps around it
};

/// At `time_s` the listed robots get `target_id`, or with `leave` stop and leave the mission.
struct TargetEvent {
  double time_s = 0.0;  // s, >= 0
  std::vector<std::uint32_t> robots;
  bool leave = false;
  std::uint32_t target_id = 0;  // unused with leave
};

/// One robot's task at some time.
struct RobotTask {
  bool active = false;  // false: no target (before its first event, or after it left)
  std::uint32_t target_id = 0;
  double target_x = 0.0;  // m
  double target_y = 0.0;  // m
  double radius_m = 0.0;  // m
  std::uint32_t slot = 0;       // rank of the robot's id among its team's, 0-based
  std::uint32_t team_size = 0;  // active robots with the same target
};

/// Targets and events, events in non-decreasing time (the scenario loader checks it, with every
/// robot and target id known).
struct TargetPlan {
  std::vector<Target> targets;
  std::vector<TargetEvent> events;

  bool empty() const { return events.empty(); }
  /// The step of an event: round(time_s / step_s).
  static std::uint64_t event_step(double time_s, double step_s);
  /// Steps at which some robot's task changes, ascending, without duplicates.
  std::vector<std::uint64_t> change_steps(double step_s) const;
  /// Every listed robot's task at `step`: the events of steps <= step applied in order.
  std::map<std::uint32_t, RobotTask> tasks_at(std::uint64_t step, double step_s, const std::vector<std::uint32_t>& robots) const;
  /// The target with this id, or nullptr.
  const Target* target(std::uint32_t id) const;
};

}  // namespace robodds::model
