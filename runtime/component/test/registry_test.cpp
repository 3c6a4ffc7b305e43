#include "runtime/component/registry.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "runtime/base/error.hpp"

namespace robodds {
namespace {

class Idle : public Component {
 public:
  void configure(ComponentContext&) override {}
  void on_step(const StepInfo&) override {}
};

ComponentType idle_type(const std::string& name) {
  return {name, "does nothing", "config/" + name + ".params.yaml", [] { return std::make_unique<Idle>(); },
          [] { return params::ParamDoc{}; }, nullptr};
}

TEST(ComponentRegistry, FindsRegisteredTypesAndNamesTheKnownOnesOtherwise) {
  ComponentRegistry registry;
  registry.add(idle_type("a"));
  registry.add(idle_type("b"));
  EXPECT_EQ(registry.get("b").name, "b");
  try {
    registry.get("c");
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "unknown component type 'c' (known: a, b)");
  }
}

TEST(ComponentRegistry, AScenarioComponentOfUnknownTypeNamesTheFileTheComponentAndTheNearestType) {
  ComponentRegistry registry;
  registry.add(idle_type("pf_estimator"));
  Scenario scenario;
  scenario.file = "mission.yaml";
  scenario.components.push_back({"estimator", "pf_estimatr", {}, {}, ""});
  try {
    registry.type_of(scenario, scenario.components.front());
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(),
                 "mission.yaml: components.estimator.type: unknown component type 'pf_estimatr'; did you mean "
                 "'pf_estimator'? (known: pf_estimator)");
  }
  scenario.components.front().type = "pf_estimator";
  EXPECT_EQ(&registry.type_of(scenario, scenario.components.front()), &registry.get("pf_estimator"));
}

TEST(ComponentRegistry, RefusesIncompleteOrRepeatedRegistrations) {
  ComponentRegistry registry;
  registry.add(idle_type("a"));
  EXPECT_THROW(registry.add(idle_type("a")), ConfigError);
  ComponentType no_table = idle_type("b");
  no_table.params = nullptr;
  EXPECT_THROW(registry.add(no_table), ConfigError);
  ComponentType no_factory = idle_type("c");
  no_factory.create = nullptr;
  EXPECT_THROW(registry.add(no_factory), ConfigError);
  EXPECT_THROW(registry.add(idle_type("")), ConfigError);
  EXPECT_EQ(registry.types().size(), 1u);
}

}  // namespace
}  // namespace robodds
