#pragma once
// The generated rows of README.md's Layout: one per component folder and one per metrics module
// of the evaluator, rendered from what their registration says (type, folder, description), so
// that the README cannot name a folder, type or description the code does not have. The README
// keeps them between two marker comments; scripts/regenerate_layout_doc.sh rewrites them and
// tools/regenerate/test/layout_doc_test.cpp fails when they differ.

#include <string>
#include <vector>

#include "common/generated_block.hpp"
#include "runtime/component/registry.hpp"
#include "sim/evaluator/module/metrics_module_registry.hpp"

namespace robodds {

inline const BlockMarkers kLayoutTableMarkers{
    "<!-- component folders and metrics modules: generated from their registration by "
    "scripts/regenerate_layout_doc.sh; do not edit -->",
    "<!-- end of generated layout -->"};

/// One generated row: a folder relative to the repository root ("components/pf_estimator") and
/// what registers there.
struct RegisteredFolder {
  std::string folder;
  std::string name;  // the component type or the metrics module kind
  std::string description;
};

/// The folder of each component type, read from its defaults file (robodds_component() registers
/// <folder>/config/<type>.params.yaml), sorted by folder. std::logic_error for a defaults file
/// elsewhere: the row would name the wrong folder.
std::vector<RegisteredFolder> component_folders(const std::vector<ComponentType>& types);

/// The folder of each metrics module (robodds_metrics_module() registers it), sorted by folder.
std::vector<RegisteredFolder> metrics_module_folders(const std::vector<evaluator::MetricsModuleType>& types);

/// Two markdown tables, each line ending in '\n', separated by an empty line: the component
/// folders (folder, type, executable robodds-<type>, description) and the metrics modules
/// (folder, module, description), rows in the given order.
std::string render_layout_table(const std::vector<RegisteredFolder>& components,
                                const std::vector<RegisteredFolder>& metrics_modules);

}  // namespace robodds
