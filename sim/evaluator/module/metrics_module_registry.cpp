#include "sim/evaluator/module/metrics_module_registry.hpp"

#include <algorithm>
#include <stdexcept>

namespace robodds::evaluator {

void MetricsModuleRegistry::add(MetricsModuleType type) {
  if (type.name.empty() || !type.create) {
    throw std::logic_error("metrics module '" + type.name + "': a name and a factory are needed");
  }
  for (const MetricsModuleType& known : types_) {
    if (known.name == type.name) {
      throw std::logic_error("metrics module '" + type.name + "' is registered twice");
    }
  }
  const auto before = [](const MetricsModuleType& a, const MetricsModuleType& b) {
    return a.summary_rank != b.summary_rank ? a.summary_rank < b.summary_rank : a.name < b.name;
  };
  types_.insert(std::upper_bound(types_.begin(), types_.end(), type, before), std::move(type));
}

}  // namespace robodds::evaluator
