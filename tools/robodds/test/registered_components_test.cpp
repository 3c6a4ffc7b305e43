// The component types registered through robodds_component() / ROBODDS_REGISTER_COMPONENT.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <string>

#include "runtime/component/registry.hpp"

namespace robodds {
namespace {

ComponentRegistry registered() {
  ComponentRegistry registry;
  register_builtin_components(registry);
  return registry;
}

TEST(RegisteredComponents, NamesAreUniqueAndSorted) {
  const ComponentRegistry registry = registered();
  ASSERT_FALSE(registry.types().empty());
  std::set<std::string> seen;
  std::string previous;
  for (const ComponentType& type : registry.types()) {
    EXPECT_TRUE(seen.insert(type.name).second) << "component type '" << type.name << "' is registered twice";
    // Sorted by name: the generated registration keeps `robodds components` in a fixed order.
    EXPECT_LT(previous, type.name) << "'" << type.name << "' is registered after '" << previous << "'";
    previous = type.name;
  }
}

TEST(RegisteredComponents, EveryTypeHasADescriptionAndAnExistingParameterFile) {
  const ComponentRegistry registry = registered();
  for (const ComponentType& type : registry.types()) {
    EXPECT_FALSE(type.description.empty()) << type.name;
    const std::string path = std::string(ROBODDS_SOURCE_DIR) + "/" + type.defaults_file;
    EXPECT_TRUE(std::ifstream(path).good()) << "component type '" << type.name << "': parameter file " << type.defaults_file
                                            << " does not exist (relative to the repository root)";
  }
}

TEST(RegisteredComponents, EveryFactoryCreatesAComponent) {
  const ComponentRegistry registry = registered();
  for (const ComponentType& type : registry.types()) {
    ASSERT_TRUE(type.create) << type.name;
    EXPECT_NE(type.create(), nullptr) << type.name;
  }
}

TEST(RegisteredComponents, GetFindsEveryRegisteredType) {
  const ComponentRegistry registry = registered();
  for (const ComponentType& type : registry.types()) {
    EXPECT_EQ(registry.get(type.name).name, type.name);
  }
}

}  // namespace
}  // namespace robodds
