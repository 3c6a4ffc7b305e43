#include "tools/robodds/module_headlines.hpp"

#include "sim/evaluator/module/metrics_module_registry.hpp"

namespace robodds {

evaluator::Headline module_headlines() {
  evaluator::MetricsModuleRegistry modules;
  evaluator::register_builtin_metrics_modules(modules);
  evaluator::Headline out;
  for (const evaluator::MetricsModuleType& type : modules.types()) {
    out.insert(out.end(), type.headline.begin(), type.headline.end());
  }
  return out;
}

}  // namespace robodds
