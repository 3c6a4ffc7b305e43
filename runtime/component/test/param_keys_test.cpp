#include "runtime/component/param_keys.hpp"

#include <gtest/gtest.h>

#include "runtime/base/error.hpp"

namespace robodds {
namespace {

class Idle : public Component {
 public:
  void configure(ComponentContext&) override {}
  void on_step(const StepInfo&) override {}
};

ComponentType type_with(const std::string& name, std::vector<std::string> keys) {
  return {name, "does nothing", "config/" + name + ".params.yaml", [] { return std::make_unique<Idle>(); },
          [keys] {
            params::ParamDoc doc;
            for (const std::string& key : keys) {
              doc.params.push_back(params::ParamInfo{key, "double", "1", "m", "", "a parameter"});
            }
            return doc;
          },
          nullptr};
}

struct ParamKeys : testing::Test {
  ParamKeys() {
    registry.add(type_with("waypoint_controller", {"epsilon_m", "k_v"}));
    registry.add(type_with("plant", {"wheel_base_m"}));
    scenario.file = "s.yaml";
    ComponentSpec controller;
    controller.name = "controller";
    controller.type = "waypoint_controller";
    ComponentSpec plant;
    plant.name = "plant";
    plant.type = "plant";
    scenario.components = {controller, plant};
  }
  std::string error_of(const std::vector<std::string>& sets) {
    try {
      check_param_keys(scenario, registry, sets, "--set");
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  }
  ComponentRegistry registry;
  Scenario scenario;
};

TEST_F(ParamKeys, KnownKeysPass) {
  EXPECT_EQ(error_of({"controller.epsilon_m=0.1", "plant.wheel_base_m=0.3", "no equals sign"}), "");
}

TEST_F(ParamKeys, AKeyWithoutItsComponentGetsTheFullName) {
  EXPECT_EQ(error_of({"epsilon=0.1"}),
            "--set 'epsilon=0.1': unknown parameter 'epsilon'; did you mean 'controller.epsilon_m'? (expected "
            "component.parameter of s.yaml; `robodds components --params TYPE` lists a type's parameters)");
  EXPECT_NE(error_of({"controller.epsilon=0.1"}).find("did you mean 'controller.epsilon_m'?"), std::string::npos);
  EXPECT_NE(error_of({"plant.wheelbase_m=0.3"}).find("did you mean 'plant.wheel_base_m'?"), std::string::npos);
  EXPECT_EQ(error_of({"weather.sunny=1"}).find("did you mean"), std::string::npos);
}

}  // namespace
}  // namespace robodds
