#pragma once
// Paper 2's mission as a scenario declares it: the top-level `targets:` and `events:` (the
// runtime stores them as sections it does not read; this file registers them), parsed into a
// model::TargetPlan for the target_mission component.
//
//   targets:
//     - {id: 1, x: 1000.0, y: 1000.0, radius_m: 200.0}
//   events:
//     - {time_s: 0.0, robots: [1, 2], target: 1}
//     - {time_s: 900.0, robots: [2], leave: true}

#include "common/model/target_plan.hpp"
#include "runtime/config/scenario.hpp"

namespace robodds::system {

/// The scenario's targets and events (empty when it has none): targets with unique ids and a
/// radius > 0; events in time order within the run, each naming known robots and either a known
/// target or `leave: true`, and no robot coming back after it left. ConfigError naming the file,
/// the key (e.g. `events[1].robots[0]`) and the reason.
model::TargetPlan target_plan(const Scenario& scenario);

/// Lets scenario files have the top-level sections `targets:` and `events:` (the runtime keeps
/// them as text, register_scenario_section()); called by install_robot_system().
void register_mission_sections();

}  // namespace robodds::system
