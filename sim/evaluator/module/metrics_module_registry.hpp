#pragma once
// Metrics module types by name, registered like components (runtime/component/registry.hpp): a
// module's .cpp says ROBODDS_REGISTER_METRICS_MODULE(...) and its folder's CMakeLists.txt calls
// robodds_metrics_module(NAME ...) (cmake/RoboddsHelpers.cmake). Registration is explicit rather
// than by static initialisers, which static linking drops: CMake generates
// registered_metrics_modules.cpp (build tree), whose register_builtin_metrics_modules() calls
// each module's registration function in name order.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim/evaluator/module/headline.hpp"
#include "sim/evaluator/module/metrics_module.hpp"

namespace robodds::evaluator {

struct MetricsModuleType {
  std::string name;
  std::string description;
  /// Its folder relative to the repository root, e.g. sim/evaluator/metrics/waypoints: what the
  /// generated rows of README.md's Layout name (tools/regenerate/layout_table.hpp).
  std::string folder;
  /// Where its keys go in summary.json's "metrics", lowest first (ties by name): the shipped
  /// modules take 10 (waypoints), 20 (motion), 30 (circumnavigation), 40 (relative_pose); a new
  /// one takes a rank of its own so that the existing keys keep their places.
  int summary_rank = 0;
  std::function<std::unique_ptr<MetricsModule>()> create;
  /// Its lines of `robodds run`'s short report (headline.hpp); empty: none.
  Headline headline;
};

class MetricsModuleRegistry {
 public:
  /// std::logic_error if the type has no name or factory, or its name is taken.
  void add(MetricsModuleType type);
  /// By summary rank, then name.
  const std::vector<MetricsModuleType>& types() const { return types_; }

 private:
  std::vector<MetricsModuleType> types_;
};

/// Registers every module built with robodds_metrics_module(). Defined by the generated
/// registered_metrics_modules.cpp of robodds_registered_metrics_modules_library().
void register_builtin_metrics_modules(MetricsModuleRegistry& registry);

}  // namespace robodds::evaluator

/// Defines robodds::metrics_module_registration::register_<kind>(MetricsModuleRegistry&), which
/// adds the module `kind` (a bare identifier, the NAME of its robodds_metrics_module() call) with
/// a one-line description, its summary rank (MetricsModuleType::summary_rank), its factory
/// (std::unique_ptr<MetricsModule>()) and its headline (an expression giving the Headline, e.g.
/// a function call: `robodds run`'s short report, headline.hpp). Its folder is the one of its robodds_metrics_module()
/// call, which passes the path as ROBODDS_METRICS_MODULE_FOLDER (a module registered by hand, in a
/// test, defines it before the macro). Write it once, at global scope, in the module's .cpp.
#define ROBODDS_REGISTER_METRICS_MODULE(kind, description, summary_rank, factory, headline)                     \
  namespace robodds::metrics_module_registration {                                                              \
  void register_##kind(::robodds::evaluator::MetricsModuleRegistry& registry);                                  \
  }                                                                                                             \
  void ::robodds::metrics_module_registration::register_##kind(::robodds::evaluator::MetricsModuleRegistry& registry) { \
    registry.add({#kind, description, ROBODDS_METRICS_MODULE_FOLDER, summary_rank, factory, headline});          \
  }                                                                                                             \
  static_assert(sizeof(description) > 1, "ROBODDS_REGISTER_METRICS_MODULE(" #kind "): the description must not be empty")

/// Declares the registration function of module `kind`, at global scope, for code that registers
/// one module by hand (a test).
#define ROBODDS_DECLARE_METRICS_MODULE(kind)                                       \
  namespace robodds::metrics_module_registration {                                 \
  void register_##kind(::robodds::evaluator::MetricsModuleRegistry& registry);     \
  }                                                                                \
  static_assert(true, "ROBODDS_DECLARE_METRICS_MODULE needs a semicolon")
