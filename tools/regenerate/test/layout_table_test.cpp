// The generated rows of README.md's Layout: folders read from the registration, the rendering.
#include "tools/regenerate/layout_table.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace robodds {
namespace {

ComponentType component(const std::string& name, const std::string& defaults_file) {
  ComponentType type;
  type.name = name;
  type.description = name + " does its job";
  type.defaults_file = defaults_file;
  return type;
}

evaluator::MetricsModuleType metrics_module(const std::string& name, const std::string& folder) {
  evaluator::MetricsModuleType type;
  type.name = name;
  type.description = name + " figures";
  type.folder = folder;
  return type;
}

/// "folder name: description", one a row, to compare rows at a glance.
std::vector<std::string> lines(const std::vector<RegisteredFolder>& rows) {
  std::vector<std::string> text;
  for (const RegisteredFolder& row : rows) {
    text.push_back(row.folder + " " + row.name + ": " + row.description);
  }
  return text;
}

TEST(LayoutTable, AComponentsFolderIsThatOfItsDefaultsFileSortedByFolder) {
  EXPECT_EQ(lines(component_folders({component("plant", "sim/plant/config/plant.params.yaml"),
                                     component("pf_estimator", "components/pf_estimator/config/pf_estimator.params.yaml")})),
            (std::vector<std::string>{"components/pf_estimator pf_estimator: pf_estimator does its job",
                                      "sim/plant plant: plant does its job"}));
}

TEST(LayoutTable, ADefaultsFileOutsideTheConventionIsAnError) {
  EXPECT_THROW(component_folders({component("plant", "sim/plant/plant.params.yaml")}), std::logic_error);
  EXPECT_THROW(component_folders({component("plant", "sim/plant/config/other.params.yaml")}), std::logic_error);
}

TEST(LayoutTable, AMetricsModulesFolderIsTheRegisteredOneSortedByFolder) {
  EXPECT_EQ(lines(metrics_module_folders({metrics_module("waypoints", "sim/evaluator/metrics/waypoints"),
                                          metrics_module("motion", "sim/evaluator/metrics/motion")})),
            (std::vector<std::string>{"sim/evaluator/metrics/motion motion: motion figures",
                                      "sim/evaluator/metrics/waypoints waypoints: waypoints figures"}));
}

TEST(LayoutTable, RendersATableOfComponentsThenOneOfMetricsModules) {
  EXPECT_EQ(render_layout_table({{"components/pf_estimator", "pf_estimator", "particle filter: a -> b"},
                                 {"sim/plant", "plant", "the plant"}},
                                {{"sim/evaluator/metrics/motion", "motion", "extremes"}}),
            "| component folder | type | executable | what (its registered description) |\n"
            "|---|---|---|---|\n"
            "| `components/pf_estimator/` | `pf_estimator` | `robodds-pf-estimator` | particle filter: a -> b |\n"
            "| `sim/plant/` | `plant` | `robodds-plant` | the plant |\n"
            "\n"
            "| evaluator's metrics module | module | what (its registered description) |\n"
            "|---|---|---|\n"
            "| `sim/evaluator/metrics/motion/` | `motion` | extremes |\n");
}

TEST(LayoutTable, ABarInADescriptionDoesNotEndItsCell) {
  const std::string table = render_layout_table({{"sim/plant", "plant", "a | b"}}, {});
  EXPECT_NE(table.find("| `robodds-plant` | a \\| b |\n"), std::string::npos) << table;
}

}  // namespace
}  // namespace robodds
