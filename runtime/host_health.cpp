#include "runtime/host_health.hpp"

namespace robodds {

ComponentHealth component_health(const std::string& component, const std::vector<std::unique_ptr<InputBase>>& inputs) {
  ComponentHealth health;
  health.component = component;
  for (const auto& input : inputs) {
    health.inputs.push_back(InputHealth{input->topic(), input->counts()});
  }
  return health;
}

}  // namespace robodds
