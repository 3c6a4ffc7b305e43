// Drift test: every registered component's checked-in config/<name>.params.yaml must be what its
// parameter table renders. On failure it prints the diff and the command that regenerates it.
#include "tools/robodds/params_files.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "runtime/base/error.hpp"
#include "runtime/component/registry.hpp"

namespace robodds {
namespace {

const ComponentRegistry& registry() {
  static const ComponentRegistry registered = [] {
    ComponentRegistry r;
    register_builtin_components(r);
    return r;
  }();
  return registered;
}

std::vector<std::string> registered_names() {
  std::vector<std::string> names;
  for (const ComponentType& type : registry().types()) {
    names.push_back(type.name);
  }
  return names;
}

// One test per registered component type, named after it.
class ParamsFileTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ParamsFileTest, CheckedInDefaultsFileIsTheRenderedTable) {
  const ComponentType& type = registry().get(GetParam());
  const std::string path = std::string(ROBODDS_SOURCE_DIR) + "/" + type.defaults_file;
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << "cannot read " << path;
  std::ostringstream checked_in;
  checked_in << in.rdbuf();
  const std::string diff = params_file_diff(checked_in.str(), expected_params_file(type));
  EXPECT_TRUE(diff.empty()) << type.defaults_file << " differs from the parameter table of '" << type.name
                      << "' (- file, + table):\n"
                      << diff << "Change the C++ (the parameter table, or the struct's member initialiser for a default), not the file, "
                      << "and run " << kRegenerateParamsCommand;
}

TEST_P(ParamsFileTest, EveryParameterHasADescription) {
  const params::ParamDoc doc = registry().get(GetParam()).params();
  // A component may have no parameters (target_mission: its mission is the scenario's), but then
  // its table's summary says what it does.
  ASSERT_FALSE(doc.params.empty() && doc.summary.empty()) << GetParam() << ": no parameters and no description";
  for (const params::ParamInfo& info : doc.params) {
    EXPECT_FALSE(info.description.empty()) << GetParam() << ": " << info.key << " has no description";
  }
}

// What `robodds components --params NAME` prints: one row per key, starting with the key and its type.
TEST_P(ParamsFileTest, ParamsTableHasARowPerKey) {
  const std::string table = component_params_text(registry(), GetParam(), false);
  for (const params::ParamInfo& info : registry().get(GetParam()).params().params) {
    EXPECT_NE(table.find("\n" + info.key + " "), std::string::npos) << GetParam() << ": no row for " << info.key << " in\n" << table;
    EXPECT_FALSE(info.type.empty()) << GetParam() << ": " << info.key << " has no type";
  }
}

INSTANTIATE_TEST_SUITE_P(AllComponents, ParamsFileTest, ::testing::ValuesIn(registered_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(ParamsFileDiff, ShowsRemovedAndAddedLines) {
  EXPECT_EQ(params_file_diff("a: 1\nb: 2\nc: 3\n", "a: 1\nb: 5\nc: 3\n"), "- b: 2\n+ b: 5\n");
  EXPECT_EQ(params_file_diff("a: 1\n", "a: 1\n"), "");
}

TEST(ComponentParamsText, TableAndYamlOfOneComponent) {
  const std::string table = component_params_text(registry(), "plant", false);
  EXPECT_NE(table.find("KEY "), std::string::npos) << table;
  EXPECT_NE(table.find("\ncommand_timeout_s       double  0.5      s     > 0  "), std::string::npos) << table;
  EXPECT_EQ(component_params_text(registry(), "plant", true), expected_params_file(registry().get("plant")));
  EXPECT_THROW(component_params_text(registry(), "plantt", false), ConfigError);
}

}  // namespace
}  // namespace robodds
