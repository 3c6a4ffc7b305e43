// add_components(): "GROUP:NAME:TYPE" joins the scenario's group; bad specs named.
#include "runtime/launch/added_components.hpp"

#include <gtest/gtest.h>

#include <string>

#include "runtime/base/error.hpp"

namespace robodds {
namespace {

Scenario two_groups() {
  Scenario s;
  s.file = "s.yaml";
  s.components = {ComponentSpec{"a", "ta", {}, {}, ""}, ComponentSpec{"e", "te", {}, {}, ""}};
  s.groups = {GroupSpec{"work", {"a"}}, GroupSpec{"evaluation", {"e"}}};
  return s;
}

std::string error_of(Scenario s, const std::string& spec) {
  try {
    add_components(s, {spec});
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(AddedComponents, JoinsTheGroup) {
  Scenario s = two_groups();
  add_components(s, {added_component_spec("evaluation", "rec", "run_recorder")});
  ASSERT_EQ(s.components.size(), 3u);
  EXPECT_EQ(s.components.back().name, "rec");
  EXPECT_EQ(s.components.back().type, "run_recorder");
  EXPECT_TRUE(s.components.back().robots.empty()) << "every robot";
  EXPECT_EQ(s.groups[1].components, (std::vector<std::string>{"e", "rec"}));
}

TEST(AddedComponents, NamesABadSpec) {
  EXPECT_NE(error_of(two_groups(), "evaluation:rec").find("expected GROUP:NAME:TYPE"), std::string::npos);
  EXPECT_NE(error_of(two_groups(), "evaluation::t").find("expected GROUP:NAME:TYPE"), std::string::npos);
  EXPECT_NE(error_of(two_groups(), "nope:rec:t").find("no group 'nope'"), std::string::npos);
  EXPECT_NE(error_of(two_groups(), "work:e:t").find("already has a component 'e'"), std::string::npos);
}

}  // namespace
}  // namespace robodds
