#include "system/robot_facts.hpp"

#include <string>

#include "common/model/uwb_array_params.hpp"
#include "common/did_you_mean.hpp"
#include "runtime/base/error.hpp"
#include "runtime/base/log.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "system/mission_plan.hpp"

namespace robodds::system {
namespace {

constexpr const char* kRobotBody = "robot_body";
constexpr const char* kUwbArray = "uwb_array";
constexpr const char* kRangeAccelBound = "range_accel_bound_mps2";
/// Every kind of fact, in the order an error lists them: one table, so the checks and the list
/// cannot drift apart.
struct FactKind {
  const char* name;
  bool is_map;     // a map of keys (robot_body: {...}), else one number
  bool per_robot;  // a robot may declare it for itself
};
constexpr FactKind kFactKinds[] = {{kRobotBody, true, true}, {kUwbArray, true, false}, {kRangeAccelBound, false, false}};

const FactKind* fact_kind(const std::string& name) {
  for (const FactKind& kind : kFactKinds) {
    if (name == kind.name) {
      return &kind;
    }
  }
  return nullptr;
}

std::string known_facts() {
  std::string list;
  for (const FactKind& kind : kFactKinds) {
    list += (list.empty() ? "" : ", ") + std::string(kind.name);
  }
  return list;
}

/// The entries of `facts` under "<group>.", without that prefix, each naming the group in its origin.
FlatParams fact_group(const FlatParams& facts, const std::string& group) {
  FlatParams out;
  const std::string prefix = group + ".";
  for (const auto& [key, entry] : facts) {
    if (key.compare(0, prefix.size(), prefix) == 0) {
      out[key.substr(prefix.size())] = ParamEntry{entry.yaml, entry.file + "." + group};
    }
  }
  return out;
}

/// Every key of `facts` names a known fact, maps where a map is due; a robot's facts only those
/// of one robot.
void check_known(const FlatParams& facts, bool of_one_robot) {
  for (const auto& [key, entry] : facts) {
    const std::string group = key.substr(0, key.find('.'));
    const FactKind* kind = fact_kind(group);
    if (kind == nullptr) {
      const std::string known = known_facts();
      throw ConfigError(located(entry.file, key, "unknown fact" + did_you_mean(group, listed_names(known)) + " (known: " + known + ")"));
    }
    if (of_one_robot && !kind->per_robot) {
      throw ConfigError(located(entry.file, key, "a fact of the whole scenario (under the top-level facts:), not of one robot"));
    }
    if (kind->is_map && group == key) {
      throw ConfigError(located(entry.file, key, "expected a map of its keys (e.g. robot_body: {wheel_base_m: 0.3})"));
    }
    if (!kind->is_map && group != key) {
      throw ConfigError(located(entry.file, group, "expected a number, not a map"));
    }
  }
}

}  // namespace

model::RobotBody robot_body(const Scenario& scenario, std::uint32_t robot_id) {
  const auto& table = model::robot_body_param_table();
  const FlatParams merged = merge_params(default_params(table.doc(), "built-in robot_body"),
                                         fact_group(scenario.facts_of(robot_id), kRobotBody));
  ParamReader reader(kRobotBody, merged);
  return read_params(reader, table);
}

model::UwbArray uwb_array(const Scenario& scenario) {
  const auto& table = model::uwb_array_param_table();
  const FlatParams merged =
      merge_params(default_params(table.doc(), "built-in uwb_array"), fact_group(scenario.facts, kUwbArray));
  ParamReader reader(kUwbArray, merged);
  const model::UwbArrayParams params = read_params(reader, table);
  reader.check([&] { params.validate(); });
  return params.array();
}

RangeAccelBound range_accel_bound(const Scenario& scenario) {
  RangeAccelBound bound;
  const auto it = scenario.facts.find(kRangeAccelBound);
  if (it == scenario.facts.end()) {
    bound.key = std::string("facts.") + kRangeAccelBound + " (default)";
    return bound;
  }
  ParamReader reader(it->second.file, FlatParams{{kRangeAccelBound, it->second}});
  bound.mps2 = reader.get_double(kRangeAccelBound);
  if (!(bound.mps2 > 0.0)) {
    throw ConfigError(located(it->second.file, kRangeAccelBound, "must be > 0 m/s^2 (got " + it->second.yaml + ")"));
  }
  bound.declared = true;
  bound.key = it->second.file + "." + kRangeAccelBound;
  return bound;
}

void check_facts(const Scenario& scenario) {
  check_known(scenario.facts, false);
  for (const RobotSpec& robot : scenario.robots) {
    check_known(robot.facts, true);
    robot_body(scenario, robot.id);
  }
  uwb_array(scenario);
  range_accel_bound(scenario);
  target_plan(scenario);
}

void register_system_checks(ComponentRegistry& registry) { registry.add_scenario_check(check_facts); }

}  // namespace robodds::system
