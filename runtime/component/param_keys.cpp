#include "runtime/component/param_keys.hpp"

#include <algorithm>

#include "common/did_you_mean.hpp"
#include "runtime/base/error.hpp"
#include "runtime/config/param_table_reader.hpp"

namespace robodds {

void check_param_keys(const Scenario& scenario, const ComponentRegistry& registry,
                      const std::vector<std::string>& assignments, const std::string& option) {
  std::vector<std::string> known;
  for (const ComponentSpec& component : scenario.components) {
    for (const auto& [key, entry] : default_params(registry.type_of(scenario, component).params(), component.type)) {
      known.push_back(component.name + "." + key);
    }
  }
  for (const std::string& text : assignments) {
    const std::size_t equals = text.find('=');
    if (equals == std::string::npos) {
      continue;
    }
    const std::string key = text.substr(0, equals);
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      throw ConfigError(option + " '" + text + "': unknown parameter '" + key + "'" + did_you_mean(key, known) +
                        " (expected component.parameter of " + scenario.file +
                        "; `robodds components --params TYPE` lists a type's parameters)");
    }
  }
}

}  // namespace robodds
