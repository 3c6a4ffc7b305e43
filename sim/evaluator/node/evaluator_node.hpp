#pragma once
#include <memory>

#include "runtime/component/component.hpp"
#include "sim/evaluator/module/metrics_module_registry.hpp"

namespace robodds::evaluator {
/// Records topics to CSV as samples arrive and writes summary.json (status, metrics, run,
/// standby, health) at the end of the run or when it fails; the metrics come from every
/// registered metrics module (register_builtin_metrics_modules()).
std::unique_ptr<Component> make_evaluator_node();
/// The same with the metrics modules of `modules` only (a test's own module).
std::unique_ptr<Component> make_evaluator_node_with_modules(MetricsModuleRegistry modules);
}  // namespace robodds::evaluator
