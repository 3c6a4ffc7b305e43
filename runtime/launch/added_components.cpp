#include "runtime/launch/added_components.hpp"

#include <algorithm>

#include "common/did_you_mean.hpp"
#include "runtime/base/error.hpp"

namespace robodds {

std::string added_component_spec(const std::string& group, const std::string& name, const std::string& type) {
  return group + ":" + name + ":" + type;
}

void add_components(Scenario& scenario, const std::vector<std::string>& specs) {
  for (const std::string& spec : specs) {
    const std::size_t first = spec.find(':');
    const std::size_t second = first == std::string::npos ? first : spec.find(':', first + 1);
    if (second == std::string::npos || spec.find(':', second + 1) != std::string::npos || first == 0 ||
        second == first + 1 || second + 1 == spec.size()) {
      throw ConfigError("--add-component '" + spec + "': expected GROUP:NAME:TYPE");
    }
    const std::string group = spec.substr(0, first);
    ComponentSpec component;
    component.name = spec.substr(first + 1, second - first - 1);
    component.type = spec.substr(second + 1);
    auto g = std::find_if(scenario.groups.begin(), scenario.groups.end(), [&](const GroupSpec& s) { return s.name == group; });
    if (g == scenario.groups.end()) {
      std::vector<std::string> names;
      for (const GroupSpec& known : scenario.groups) {
        names.push_back(known.name);
      }
      throw ConfigError("--add-component '" + spec + "': " + scenario.file + " has no group '" + group + "'" + did_you_mean(group, names));
    }
    if (std::any_of(scenario.components.begin(), scenario.components.end(),
                    [&](const ComponentSpec& c) { return c.name == component.name; })) {
      throw ConfigError("--add-component '" + spec + "': " + scenario.file + " already has a component '" + component.name + "'");
    }
    g->components.push_back(component.name);
    scenario.components.push_back(std::move(component));
  }
}

}  // namespace robodds
