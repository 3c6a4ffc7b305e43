#include "runtime/launch/standalone_scenario.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "common/number_parse.hpp"
#include "runtime/base/error.hpp"

namespace robodds {
namespace {

[[noreturn]] void bad_robot(const std::string& text, const std::string& reason) {
  throw ConfigError("--robot '" + text + "': " + reason + " (expected ID or ID:X,Y,THETA, e.g. 1 or 1:50,10,0)");
}

double parse_coordinate(const std::string& robot, const std::string& text, const char* what) {
  const std::optional<double> value = parse_finite_number(text);
  if (!value) {
    bad_robot(robot, std::string(what) + " '" + text + "' is not a finite number");
  }
  return *value;
}

}  // namespace

RobotSpec parse_robot(const std::string& text) {
  const std::size_t colon = text.find(':');
  const std::optional<std::uint64_t> id = parse_whole_number(text.substr(0, colon), 0xffffffffULL);
  if (!id) {
    bad_robot(text, "the id is not a whole number 0..4294967295");
  }
  RobotSpec robot;
  robot.id = static_cast<std::uint32_t>(*id);
  if (colon == std::string::npos) {
    return robot;
  }
  std::vector<std::string> parts;
  std::stringstream pose(text.substr(colon + 1));
  for (std::string part; std::getline(pose, part, ',');) {
    parts.push_back(part);
  }
  if (parts.size() != 3 || text.back() == ',') {
    bad_robot(text, "the pose needs three numbers X,Y,THETA");
  }
  robot.x = parse_coordinate(text, parts[0], "X");
  robot.y = parse_coordinate(text, parts[1], "Y");
  robot.theta = parse_coordinate(text, parts[2], "THETA");
  return robot;
}

Scenario standalone_scenario(const HostArgs& args) {
  if (args.type.empty()) {
    throw ConfigError("a component without a scenario needs its type (--type)");
  }
  if (args.robots.empty()) {
    throw ConfigError(args.type + ": give the robots it serves with --robot ID (or ID:X,Y,THETA), e.g. --robot 1");
  }
  Scenario scenario;
  scenario.file = "(command line of " + args.type + ")";
  scenario.name = args.type;
  scenario.description = "component " + args.type + " without a scenario file";
  scenario.step_s = args.step_s.value_or(kStandaloneStepS);
  // "Until stopped" is at most kMaxLastStep steps, so that a short --step still fits.
  scenario.duration_s = args.duration_s.value_or(std::min(kUntilStoppedS, static_cast<double>(kMaxLastStep) * scenario.step_s));
  scenario.seed = args.seed.value_or(1);
  checked_last_step(scenario.step_s, scenario.duration_s, "", "--step");
  std::set<std::uint32_t> ids;
  ComponentSpec component;
  component.name = args.name.empty() ? args.type : args.name;
  component.type = args.type;
  for (const std::string& text : args.robots) {
    const RobotSpec robot = parse_robot(text);
    if (!ids.insert(robot.id).second) {
      bad_robot(text, "robot " + std::to_string(robot.id) + " is given twice");
    }
    scenario.robots.push_back(robot);
    component.robots.push_back(robot.id);
  }
  if (!args.params.empty()) {
    // Its `facts:` (e.g. robot_body: the robot's physical description) are the scenario's shared
    // facts; every other key is a parameter of the component.
    const std::string facts_prefix = "facts.";
    for (auto& [key, entry] : load_param_file(args.params)) {
      if (key.compare(0, facts_prefix.size(), facts_prefix) == 0) {
        scenario.facts[key.substr(facts_prefix.size())] = ParamEntry{entry.yaml, entry.file + ": facts"};
      } else {
        component.overrides[key] = entry;
      }
    }
  }
  scenario.components.push_back(component);
  scenario.groups.push_back(GroupSpec{args.member.empty() ? component.name : args.member, {component.name}});
  return scenario;
}

}  // namespace robodds
