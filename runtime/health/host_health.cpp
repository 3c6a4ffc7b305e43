#include "runtime/health/host_health.hpp"

namespace robodds {

ComponentHealth component_health(const std::string& component, const std::vector<std::unique_ptr<InputBase>>& inputs) {
  ComponentHealth health;
  health.component = component;
  for (const auto& input : inputs) {
    health.inputs.push_back(InputHealth{input->topic(), input->counts()});
  }
  return health;
}

void add_stage_timing(std::vector<StageTiming>& timing, const std::string& component, const ComputeTimes& times) {
  for (ComputeTimes::Summary& summary : times.summaries()) {
    timing.push_back(StageTiming{component, std::move(summary)});
  }
}

}  // namespace robodds
