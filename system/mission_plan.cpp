#include "system/mission_plan.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "common/number_text.hpp"
#include "runtime/config/yaml_reader.hpp"

namespace robodds::system {
namespace {

using SectionReader = YamlReader;  // errors name the scenario file and a key under it

bool has_section(const Scenario& scenario, const char* name) { return scenario.sections.count(name) != 0; }
YAML::Node section(const Scenario& scenario, const char* name) { return YAML::Load(scenario.sections.at(name).yaml); }

void parse_targets(const YAML::Node& node, const SectionReader& in, model::TargetPlan& plan) {
  if (!node.IsSequence() || node.size() == 0) {
    in.fail("targets", "expected a non-empty list of {id, x, y, radius_m}");
  }
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string key = "targets[" + std::to_string(i) + "]";
    const YAML::Node& t = node[i];
    if (!t.IsMap()) {
      in.fail(key, "expected a map {id, x, y, radius_m}");
    }
    in.only_keys(t, key, {"id", "x", "y", "radius_m"}, "id, x, y, radius_m");
    model::Target target;
    target.id = in.scalar<std::uint32_t>(t["id"], key + ".id", "a target id (non-negative integer)");
    target.x = in.finite(t["x"], key + ".x");
    target.y = in.finite(t["y"], key + ".y");
    target.radius_m = in.finite(t["radius_m"], key + ".radius_m");
    if (target.radius_m <= 0.0) {
      in.fail(key + ".radius_m", "must be > 0 (got " + shortest_text(target.radius_m) + ")");
    }
    if (plan.target(target.id) != nullptr) {
      in.fail(key + ".id", "duplicate target id " + std::to_string(target.id));
    }
    plan.targets.push_back(target);
  }
}

void parse_events(const YAML::Node& node, const SectionReader& in, const Scenario& s, model::TargetPlan& plan) {
  if (!node.IsSequence() || node.size() == 0) {
    in.fail("events", "expected a non-empty list of {time_s, robots, target} or {time_s, robots, leave: true}");
  }
  if (plan.targets.empty()) {
    in.fail("events", "events assign targets: declare them under 'targets'");
  }
  std::set<std::uint32_t> left;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string key = "events[" + std::to_string(i) + "]";
    const YAML::Node& e = node[i];
    if (!e.IsMap()) {
      in.fail(key, "expected a map {time_s, robots, target} or {time_s, robots, leave: true}");
    }
    in.only_keys(e, key, {"time_s", "robots", "target", "leave"}, "time_s, robots, target, leave");
    model::TargetEvent event;
    event.time_s = in.finite(e["time_s"], key + ".time_s");
    if (event.time_s < 0.0 || event.time_s > s.duration_s) {
      in.fail(key + ".time_s", shortest_text(event.time_s) + " s is outside the run (0 to duration_s " +
                                   shortest_text(s.duration_s) + " s)");
    }
    if (!plan.events.empty() && event.time_s < plan.events.back().time_s) {
      in.fail(key + ".time_s", shortest_text(event.time_s) + " s is before the previous event's " +
                                   shortest_text(plan.events.back().time_s) + " s (list events in time order)");
    }
    event.leave = e["leave"] && in.scalar<bool>(e["leave"], key + ".leave", "true or false");
    if (event.leave == static_cast<bool>(e["target"])) {
      in.fail(key, "give either 'target: ID' or 'leave: true'");
    }
    if (!event.leave) {
      event.target_id = in.scalar<std::uint32_t>(e["target"], key + ".target", "a target id");
      if (plan.target(event.target_id) == nullptr) {
        in.fail(key + ".target", "unknown target " + std::to_string(event.target_id) + " (not in 'targets')");
      }
    }
    const YAML::Node& robots = e["robots"];
    if (!robots || !robots.IsSequence() || robots.size() == 0) {
      in.fail(key + ".robots", "expected a non-empty list of robot ids");
    }
    for (std::size_t j = 0; j < robots.size(); ++j) {
      const std::string rkey = key + ".robots[" + std::to_string(j) + "]";
      const auto id = in.scalar<std::uint32_t>(robots[j], rkey, "a robot id");
      const bool known = std::any_of(s.robots.begin(), s.robots.end(), [&](const RobotSpec& r) { return r.id == id; });
      if (!known) {
        in.fail(rkey, "unknown robot " + std::to_string(id) + " (not in 'robots')");
      }
      if (left.count(id) != 0) {
        in.fail(rkey, "robot " + std::to_string(id) + " left the mission at an earlier event and cannot come back");
      }
      event.robots.push_back(id);
    }
    if (event.leave) {
      left.insert(event.robots.begin(), event.robots.end());
    }
    plan.events.push_back(std::move(event));
  }
}

}  // namespace

void register_mission_sections() {
  register_scenario_section("targets");
  register_scenario_section("events");
}

model::TargetPlan target_plan(const Scenario& scenario) {
  const SectionReader in(scenario.file);
  model::TargetPlan plan;
  if (has_section(scenario, "targets")) {
    parse_targets(section(scenario, "targets"), in, plan);
  }
  if (has_section(scenario, "events")) {
    parse_events(section(scenario, "events"), in, scenario, plan);
  }
  return plan;
}

}  // namespace robodds::system
