#pragma once
// The system layer's shared facts: what several components of a scenario must agree on,
// declared once under the scenario's `facts:` (and a robot's own `facts:`), read here with a type.
// Components read a fact through these functions; none inspects another component's type or
// parameters (tests/layering checks it).
//
//   facts:
//     robot_body: {wheel_base_m: 0.3, max_wheel_speed_mps: 1.5}   # every robot
//   robots:
//     - {id: 2, x: 1, y: 0, facts: {robot_body: {wheel_base_m: 0.35}}}  # robot 2 differs
//
// Facts: robot_body (per robot), uwb_array and range_accel_bound_mps2 (of the whole scenario).
// The runtime stores the facts flattened and reads none (runtime/config/scenario.hpp); check_facts()
// runs before anything starts as a registered scenario check.

#include <cstdint>
#include <string>

#include "common/model/robot_body.hpp"
#include "common/model/uwb_array.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/config/scenario.hpp"

namespace robodds::system {

/// Robot `robot_id`'s body: model::robot_body_param_table()'s defaults under the scenario's
/// `facts: robot_body:` and the robot's own. ConfigError naming the file, the key and the reason
/// (an unknown key, a wrong type, a value out of range, an unknown robot).
model::RobotBody robot_body(const Scenario& scenario, std::uint32_t robot_id);

/// The UWB array every robot carries (paper 3): model::uwb_array_param_table()'s defaults
/// (array_side_m, nodes_m) under the scenario's `facts: uwb_array:`. A fact of the whole scenario:
/// the sensor and the estimator model one array for all robots. ConfigError naming file and key.
model::UwbArray uwb_array(const Scenario& scenario);

/// The bound on |r''| (the range acceleration, m/s^2) a circumnavigation is designed for (paper 2):
/// the guidance law keeps |r''| below it, the super-twisting observer's gain b must not be below
/// it (each checked at start-up), the evaluator counts the samples above it.
struct RangeAccelBound {
  double mps2 = 2.2;      // m/s^2, > 0; the default: what paper 2's default gains are tuned for
  bool declared = false;  // the scenario declares it (`facts: range_accel_bound_mps2:`)
  std::string key;        // where it comes from, for messages: "<file>: facts.range_accel_bound_mps2" or "(default)"
};
RangeAccelBound range_accel_bound(const Scenario& scenario);

/// Every fact of the scenario and of each robot is known and valid, and so is its mission plan
/// (system/mission_plan.hpp). ConfigError otherwise.
void check_facts(const Scenario& scenario);

/// Adds check_facts() to the registry's scenario checks (run before a run or a host starts).
void register_system_checks(ComponentRegistry& registry);

}  // namespace robodds::system
