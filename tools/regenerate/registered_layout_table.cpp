#include "tools/regenerate/registered_layout_table.hpp"

#include "runtime/component/registry.hpp"
#include "sim/evaluator/module/metrics_module_registry.hpp"
#include "tools/regenerate/layout_table.hpp"

namespace robodds {

std::string render_registered_layout_table() {
  ComponentRegistry components;
  register_builtin_components(components);
  evaluator::MetricsModuleRegistry metrics_modules;
  evaluator::register_builtin_metrics_modules(metrics_modules);
  return render_layout_table(component_folders(components.types()), metrics_module_folders(metrics_modules.types()));
}

}  // namespace robodds
