#pragma once
// One component without a scenario file: what a component executable (robodds-<type>) or
// `robodds host --type` runs on a robot. The command line names the type, the robots, the step
// and a file of the component's own parameters; this turns it into the one-component, one-group
// scenario the host runs. With the same instance name, seed, step, robots and parameters as in
// a scenario, the component's output is the same as there (its random streams derive from the
// scenario seed and its instance name).

#include "runtime/launch/host_args.hpp"
#include "runtime/config/scenario.hpp"

namespace robodds {

/// The scenario of `args.type` alone: robots from `args.robots` ("ID" or "ID:X,Y,THETA"),
/// step `args.step_s` (default kStandaloneStepS), duration `args.duration_s` (default
/// kUntilStoppedS), seed `args.seed` (default 1), the component named `args.name` (default the
/// type) with the keys of the YAML file `args.params` as overrides, in one group named
/// `args.member` (default the instance name). ConfigError naming the option or file and the
/// reason on bad input (a robot that does not parse or repeats, a step that is not positive).
/// Unknown parameter keys are reported when the host configures the component.
Scenario standalone_scenario(const HostArgs& args);

/// Parses one --robot value: "ID" (pose 0, 0, 0) or "ID:X,Y,THETA" (m, m, rad).
RobotSpec parse_robot(const std::string& text);

}  // namespace robodds
