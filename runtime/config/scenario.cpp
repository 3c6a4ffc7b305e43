#include "runtime/config/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <set>

#include "common/did_you_mean.hpp"
#include "common/number_text.hpp"
#include "runtime/base/error.hpp"
#include "runtime/config/yaml_reader.hpp"

namespace robodds {
namespace {

const std::set<std::string> kTopLevelKeys = {"name", "description", "step_s", "duration_s", "seed",
                                             "robots", "components", "groups", "facts"};

/// The top-level sections the layer above reads (register_scenario_section); a function-local
/// static, so registrations from other libraries' static initialisers find it constructed.
std::set<std::string>& registered_sections() {
  static std::set<std::string> sections;
  return sections;
}
std::mutex& sections_mutex() {
  static std::mutex mutex;
  return mutex;
}
bool is_registered_section(const std::string& key) {
  std::lock_guard<std::mutex> lock(sections_mutex());
  return registered_sections().count(key) != 0;
}
std::string known_top_level_keys() {
  std::string text = "name, description, step_s, duration_s, seed, robots, components, groups, facts";
  std::lock_guard<std::mutex> lock(sections_mutex());
  for (const std::string& section : registered_sections()) {
    text += ", " + section;
  }
  return text;
}

std::vector<std::string> component_names(const Scenario& s) {
  std::vector<std::string> names;
  for (const ComponentSpec& c : s.components) {
    names.push_back(c.name);
  }
  return names;
}

class ScenarioParser : public YamlReader {
 public:
  explicit ScenarioParser(std::string file) : YamlReader(std::move(file)) {}

  Scenario parse(const YAML::Node& root) const {
    if (!root.IsMap()) {
      fail("", "expected a map at the top level");
    }
    for (const auto& item : root) {
      const std::string key = item.first.as<std::string>();
      if (kTopLevelKeys.count(key) == 0 && !is_registered_section(key)) {
        const std::string known = known_top_level_keys();
        fail(key, "unknown key" + did_you_mean(key, listed_names(known)) + " (known: " + known + ")");
      }
    }
    Scenario s;
    s.file = file();
    s.name = scalar<std::string>(root["name"], "name", "a string");
    if (root["description"]) {
      s.description = scalar<std::string>(root["description"], "description", "a string");
    }
    s.step_s = finite(root["step_s"], "step_s");
    if (s.step_s <= 0.0) {
      fail("step_s", "must be > 0");
    }
    s.duration_s = finite(root["duration_s"], "duration_s");
    if (s.duration_s <= 0.0) {
      fail("duration_s", "must be > 0");
    }
    checked_last_step(s.step_s, s.duration_s, file(), "step_s");
    s.seed = scalar<std::uint64_t>(root["seed"], "seed", "a non-negative integer");
    parse_robots(root["robots"], s);
    parse_components(root["components"], s);
    parse_groups(root["groups"], s);
    check_standbys(s);
    s.facts = facts(root["facts"], "facts");
    for (const auto& item : root) {
      const std::string key = item.first.as<std::string>();
      if (kTopLevelKeys.count(key) == 0) {  // a section the layer above reads: its YAML text
        YAML::Emitter emitter;
        emitter << YAML::Flow << item.second;
        s.sections[key] = ParamEntry{emitter.c_str(), file()};
      }
    }
    return s;
  }

 private:
  void parse_robots(const YAML::Node& node, Scenario& s) const {
    if (!node || !node.IsSequence() || node.size() == 0) {
      fail("robots", "expected a non-empty list of {id, x, y, theta}");
    }
    std::set<std::uint32_t> ids;
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string key = "robots[" + std::to_string(i) + "]";
      const YAML::Node& r = node[i];
      if (!r.IsMap()) {
        fail(key, "expected a map {id, x, y, theta}");
      }
      for (const auto& item : r) {
        const std::string k = item.first.as<std::string>();
        if (k != "id" && k != "x" && k != "y" && k != "theta" && k != "facts") {
          fail(key + "." + k, "unknown key" + did_you_mean(k, {"id", "x", "y", "theta", "facts"}) + " (known: id, x, y, theta, facts)");
        }
      }
      RobotSpec robot;
      robot.id = scalar<std::uint32_t>(r["id"], key + ".id", "a robot id (non-negative integer)");
      robot.x = r["x"] ? finite(r["x"], key + ".x") : 0.0;
      robot.y = r["y"] ? finite(r["y"], key + ".y") : 0.0;
      robot.theta = r["theta"] ? finite(r["theta"], key + ".theta") : 0.0;
      robot.facts = facts(r["facts"], key + ".facts");
      if (!ids.insert(robot.id).second) {
        fail(key + ".id", "duplicate robot id " + std::to_string(robot.id));
      }
      s.robots.push_back(robot);
    }
  }

  void parse_components(const YAML::Node& node, Scenario& s) const {
    if (!node || !node.IsSequence() || node.size() == 0) {
      fail("components", "expected a non-empty list of {name, type, robots, params}");
    }
    std::set<std::string> names;
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string key = "components[" + std::to_string(i) + "]";
      const YAML::Node& c = node[i];
      if (!c.IsMap()) {
        fail(key, "expected a map {name, type, robots, params}");
      }
      for (const auto& item : c) {
        const std::string k = item.first.as<std::string>();
        if (k != "name" && k != "type" && k != "robots" && k != "params" && k != "standby_for") {
          fail(key + "." + k, "unknown key" + did_you_mean(k, {"name", "type", "robots", "params", "standby_for"}) +
                               " (known: name, type, robots, params, standby_for)");
        }
      }
      ComponentSpec spec;
      spec.name = scalar<std::string>(c["name"], key + ".name", "a string");
      spec.type = c["type"] ? scalar<std::string>(c["type"], key + ".type", "a string") : spec.name;
      if (!names.insert(spec.name).second) {
        fail(key + ".name", "duplicate component name '" + spec.name + "'");
      }
      if (c["robots"]) {
        if (!c["robots"].IsSequence()) {
          fail(key + ".robots", "expected a list of robot ids");
        }
        for (std::size_t j = 0; j < c["robots"].size(); ++j) {
          const std::string rkey = key + ".robots[" + std::to_string(j) + "]";
          const auto id = scalar<std::uint32_t>(c["robots"][j], rkey, "a robot id");
          const bool known = std::any_of(s.robots.begin(), s.robots.end(), [&](const RobotSpec& r) { return r.id == id; });
          if (!known) {
            fail(rkey, "unknown robot " + std::to_string(id) + " (not in 'robots')");
          }
          spec.robots.push_back(id);
        }
      } else {
        for (const RobotSpec& r : s.robots) {
          spec.robots.push_back(r.id);
        }
      }
      if (c["standby_for"]) {
        spec.standby_for = scalar<std::string>(c["standby_for"], key + ".standby_for", "a component name");
      }
      if (c["params"]) {
        if (!c["params"].IsMap()) {
          fail(key + ".params", "expected a map of parameter overrides");
        }
        // Re-read through the same flattening as parameter files, tagging this scenario file.
        flatten_overrides(c["params"], "", spec.overrides);
      }
      s.components.push_back(std::move(spec));
    }
  }

  /// A `facts:` map (absent: none), flattened; each value remembers "<file>: <key>" as its origin,
  /// so that the layer that reads it names where it came from.
  FlatParams facts(const YAML::Node& node, const std::string& key) const {
    FlatParams out;
    if (!node) {
      return out;
    }
    if (!node.IsMap()) {
      fail(key, "expected a map of facts (e.g. robot_body: {wheel_base_m: 0.3})");
    }
    flatten_overrides(node, "", out);
    for (auto& [name, entry] : out) {
      entry.file = file() + ": " + key;
    }
    return out;
  }

  void flatten_overrides(const YAML::Node& node, const std::string& prefix, FlatParams& out) const {
    for (const auto& item : node) {
      const std::string key = prefix + item.first.as<std::string>();
      if (item.second.IsMap()) {
        flatten_overrides(item.second, key + ".", out);
      } else {
        YAML::Emitter emitter;
        emitter << YAML::Flow << item.second;
        out[key] = ParamEntry{emitter.c_str(), file()};
      }
    }
  }

  void parse_groups(const YAML::Node& node, Scenario& s) const {
    std::set<std::string> placed;
    if (node) {
      if (!node.IsMap()) {
        fail("groups", "expected a map group -> list of component names");
      }
      for (const auto& item : node) {
        GroupSpec group;
        group.name = item.first.as<std::string>();
        const std::string key = "groups." + group.name;
        if (!item.second.IsSequence() || item.second.size() == 0) {
          fail(key, "expected a non-empty list of component names");
        }
        for (const auto& member : item.second) {
          const std::string name = scalar<std::string>(member, key, "a component name");
          const bool known = std::any_of(s.components.begin(), s.components.end(),
                                         [&](const ComponentSpec& c) { return c.name == name; });
          if (!known) {
            fail(key, "unknown component '" + name + "'" + did_you_mean(name, component_names(s)));
          }
          if (!placed.insert(name).second) {
            fail(key, "component '" + name + "' is in more than one group");
          }
          group.components.push_back(name);
        }
        s.groups.push_back(std::move(group));
      }
    }
    // Components not placed in a group each run in a group of their own name.
    for (const ComponentSpec& c : s.components) {
      if (placed.count(c.name) == 0) {
        s.groups.push_back(GroupSpec{c.name, {c.name}});
      }
    }
  }

  /// A standby names a primary that is no standby, of the same type and robots, in another group.
  void check_standbys(const Scenario& s) const {
    const auto group_of = [&s](const std::string& component) {
      for (const GroupSpec& g : s.groups) {
        if (std::find(g.components.begin(), g.components.end(), component) != g.components.end()) {
          return g.name;
        }
      }
      return std::string();
    };
    for (std::size_t i = 0; i < s.components.size(); ++i) {
      const ComponentSpec& standby = s.components[i];
      if (standby.standby_for.empty()) {
        continue;
      }
      const std::string key = "components[" + std::to_string(i) + "].standby_for";
      const auto primary = std::find_if(s.components.begin(), s.components.end(),
                                        [&](const ComponentSpec& c) { return c.name == standby.standby_for; });
      if (primary == s.components.end()) {
        fail(key, "unknown component '" + standby.standby_for + "'" + did_you_mean(standby.standby_for, component_names(s)));
      }
      if (!primary->standby_for.empty()) {
        fail(key, "'" + primary->name + "' is itself a standby (for '" + primary->standby_for + "')");
      }
      if (primary->type != standby.type) {
        fail(key, "standby '" + standby.name + "' is a " + standby.type + ", its primary '" + primary->name + "' a " +
                      primary->type + " (a standby has its primary's type)");
      }
      if (primary->robots != standby.robots) {
        fail(key, "standby '" + standby.name + "' serves other robots than its primary '" + primary->name + "'");
      }
      if (group_of(primary->name) == group_of(standby.name)) {
        fail(key, "standby '" + standby.name + "' is in group '" + group_of(standby.name) + "' with its primary '" +
                      primary->name + "'; put it in another group (another process) to survive the primary's death");
      }
    }
  }

};

}  // namespace

std::uint64_t checked_last_step(double step_s, double duration_s, const std::string& file, const std::string& key) {
  if (!(step_s > 0.0) || !std::isfinite(step_s)) {
    throw ConfigError(located(file, key, "the step must be a positive, finite number of seconds (got " + shortest_text(step_s) + ")"));
  }
  if (!(duration_s > 0.0) || !std::isfinite(duration_s)) {
    throw ConfigError(
        located(file, key, "the duration must be a positive, finite number of seconds (got " + shortest_text(duration_s) + ")"));
  }
  const double last = std::round(duration_s / step_s);  // may be inf: compared as a double first
  if (!(last <= static_cast<double>(kMaxLastStep))) {
    char count[32];
    std::snprintf(count, sizeof(count), "%.3g", last);
    throw ConfigError(located(file, key,
                              "duration " + shortest_text(duration_s) + " s at step " + shortest_text(step_s) + " s is " +
                                  count + " steps, more than " + std::to_string(kMaxLastStep) +
                                  " (2^40); use a longer step or a shorter duration"));
  }
  return static_cast<std::uint64_t>(last);
}

void apply_run_overrides(Scenario& scenario, const std::optional<double>& duration_s, const std::optional<std::uint64_t>& seed) {
  if (duration_s) {
    checked_last_step(scenario.step_s, *duration_s, "", "--duration");
    scenario.duration_s = *duration_s;
  }
  if (seed) {
    scenario.seed = *seed;
  }
}

std::uint64_t Scenario::last_step() const { return checked_last_step(step_s, duration_s, file, "duration_s"); }

const ComponentSpec& Scenario::component(const std::string& component_name) const {
  for (const ComponentSpec& c : components) {
    if (c.name == component_name) {
      return c;
    }
  }
  throw ConfigError(located(file, "components", "no component named '" + component_name + "'" +
                                                    did_you_mean(component_name, component_names(*this))));
}

std::size_t Scenario::robots_served_by(const std::vector<std::string>& component_names) const {
  std::set<std::uint32_t> served;
  for (const std::string& name : component_names) {
    const ComponentSpec& spec = component(name);
    served.insert(spec.robots.begin(), spec.robots.end());
  }
  return served.size();
}

const GroupSpec& Scenario::group(const std::string& group_name) const {
  std::string known;
  std::vector<std::string> names;
  for (const GroupSpec& g : groups) {
    if (g.name == group_name) {
      return g;
    }
    known += (known.empty() ? "" : ", ") + g.name;
    names.push_back(g.name);
  }
  throw ConfigError(located(file, "groups", "no group named '" + group_name + "'" + did_you_mean(group_name, names) +
                                                " (groups: " + known + ")"));
}

const RobotSpec& Scenario::robot(std::uint32_t id) const {
  for (const RobotSpec& r : robots) {
    if (r.id == id) {
      return r;
    }
  }
  throw ConfigError(located(file, "robots", "no robot with id " + std::to_string(id)));
}

bool register_scenario_section(const std::string& name) {
  std::lock_guard<std::mutex> lock(sections_mutex());
  registered_sections().insert(name);
  return true;
}

FlatParams Scenario::facts_of(std::uint32_t id) const {
  FlatParams merged = facts;
  for (const auto& [key, entry] : robot(id).facts) {
    merged[key] = entry;
  }
  return merged;
}

Scenario load_scenario(const std::string& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (std::filesystem::is_directory(status)) {
    throw ConfigError(located(path, "", "is a directory, not a scenario file"));
  }
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    throw ConfigError(located(path, "", "is not a regular file (a scenario is a YAML file)"));
  }
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ConfigError(located(path, "", "cannot open scenario file"));
  } catch (const YAML::Exception& e) {
    throw ConfigError(located(path, "", "invalid YAML at line " + std::to_string(e.mark.line + 1) + ": " + e.msg));
  }
  return ScenarioParser(path).parse(root);
}

void apply_param_overrides(Scenario& scenario, const FlatParams& overrides, const std::string& file) {
  for (const auto& [key, entry] : overrides) {
    const std::size_t dot = key.find('.');
    const std::string component = key.substr(0, dot);
    bool found = false;
    for (ComponentSpec& c : scenario.components) {
      if (c.name == component && dot != std::string::npos) {
        c.overrides[key.substr(dot + 1)] = entry;
        found = true;
      }
    }
    if (!found) {
      std::string names;
      for (const ComponentSpec& c : scenario.components) {
        names += (names.empty() ? "" : ", ") + c.name;
      }
      throw ConfigError(located(file, key, "expected <component>.<parameter> of a scenario component: " +
                                               (dot == std::string::npos ? "no '.'" : "no component '" + component + "'" +
                                                                                          did_you_mean(component, component_names(scenario))) +
                                               " in " + scenario.file + " (components: " + names + ")"));
    }
  }
}

}  // namespace robodds
