#include "system/robot_facts.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "runtime/base/error.hpp"
#include "tests/support/temp_file.hpp"

namespace robodds::system {
namespace {

using test_support::write_test_file;

Scenario scenario_with(const std::string& facts, const std::string& robot2 = "{id: 2}") {
  return load_scenario(write_test_file("s.yaml", "name: s\nstep_s: 0.01\nduration_s: 1\nseed: 1\n" + facts +
                                                     "robots:\n  - {id: 1}\n  - " + robot2 +
                                                     "\ncomponents:\n  - {name: plant, type: plant}\n"));
}

std::string facts_error(const Scenario& s) {
  try {
    check_facts(s);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(RobotFacts, WithoutFactsEveryRobotHasTheDefaultBody) {
  const Scenario s = scenario_with("");
  EXPECT_EQ(facts_error(s), "");
  const model::RobotBody body = robot_body(s, 2);
  EXPECT_EQ(body.wheel_base_m, model::RobotBody{}.wheel_base_m);
  EXPECT_EQ(body.limits.max_speed_mps, 0.0);
  EXPECT_EQ(body.actuator.max_accel_mps2, 0.0);
}

TEST(RobotFacts, TheScenarioBodyAppliesToEveryRobotAndARobotsOwnGoesOverIt) {
  const Scenario s = scenario_with("facts:\n  robot_body: {wheel_base_m: 0.3, max_accel_mps2: 1.0, max_turn_rate_radps: 0.5}\n",
                                   "{id: 2, facts: {robot_body: {wheel_base_m: 0.35}}}");
  EXPECT_EQ(facts_error(s), "");
  EXPECT_EQ(robot_body(s, 1).wheel_base_m, 0.3);
  EXPECT_EQ(robot_body(s, 2).wheel_base_m, 0.35);
  EXPECT_EQ(robot_body(s, 2).actuator.max_accel_mps2, 1.0);  // the scenario's, not overridden
  EXPECT_EQ(robot_body(s, 1).limits.max_turn_rate_radps, 0.5);
}

TEST(RobotFacts, AnUnknownBodyKeyNamesTheFileTheKeyAndTheKnownOnes) {
  const std::string error = facts_error(scenario_with("facts:\n  robot_body: {wheelbase_m: 0.3}\n"));
  EXPECT_NE(error.find("s.yaml: facts.robot_body: wheelbase_m: unknown parameter"), std::string::npos) << error;
  EXPECT_NE(error.find("wheel_base_m"), std::string::npos) << error;
}

TEST(RobotFacts, AValueOutOfRangeNamesTheRobotsEntry) {
  const std::string error =
      facts_error(scenario_with("", "{id: 2, facts: {robot_body: {wheel_base_m: -1}}}"));
  EXPECT_NE(error.find("s.yaml: robots[1].facts.robot_body: wheel_base_m: must be > 0"), std::string::npos) << error;
}

TEST(RobotFacts, AWrongTypeIsNamed) {
  const std::string error = facts_error(scenario_with("facts:\n  robot_body: {max_speed_mps: fast}\n"));
  EXPECT_NE(error.find("facts.robot_body: max_speed_mps: expected a number, got 'fast'"), std::string::npos) << error;
}

TEST(RobotFacts, AnUnknownFactOrAFactThatIsNoMapIsRefused) {
  std::string error = facts_error(scenario_with("facts:\n  robot_mass_kg: 3\n"));
  EXPECT_NE(error.find("s.yaml: facts: robot_mass_kg: unknown fact (known: robot_body, uwb_array, range_accel_bound_mps2)"),
            std::string::npos)
      << error;
  error = facts_error(scenario_with("facts:\n  robot_body: 0.3\n"));
  EXPECT_NE(error.find("robot_body: expected a map"), std::string::npos) << error;
  error = facts_error(scenario_with("", "{id: 2, facts: {color: red}}"));
  EXPECT_NE(error.find("robots[1].facts: color: unknown fact"), std::string::npos) << error;
}

TEST(UwbArrayFact, TheDefaultSquareOrTheScenariosArrayForEveryRobot) {
  EXPECT_EQ(uwb_array(scenario_with("")).nodes_m.size(), 4u);
  const model::UwbArray square = uwb_array(scenario_with("facts:\n  uwb_array: {array_side_m: 0.8}\n"));
  ASSERT_EQ(square.nodes_m.size(), 4u);
  EXPECT_NEAR(square.nodes_m[0].norm(), 0.4 * std::sqrt(2.0), 1e-12);
  const model::UwbArray nodes = uwb_array(scenario_with("facts:\n  uwb_array: {nodes_m: [[0.3, 0], [-0.3, 0], [0, 0.3]]}\n"));
  ASSERT_EQ(nodes.nodes_m.size(), 3u);
  EXPECT_EQ(nodes.nodes_m[2].y(), 0.3);
}

TEST(UwbArrayFact, ABadArrayOrOneRobotsOwnArrayIsRefused) {
  std::string error = facts_error(scenario_with("facts:\n  uwb_array: {nodes_m: [[0.3, 0], [-0.3, 0]]}\n"));
  EXPECT_NE(error.find("s.yaml: facts.uwb_array: nodes_m:"), std::string::npos) << error;
  error = facts_error(scenario_with("facts:\n  uwb_array: {array_side_m: -1}\n"));
  EXPECT_NE(error.find("facts.uwb_array: array_side_m: must be > 0"), std::string::npos) << error;
  error = facts_error(scenario_with("", "{id: 2, facts: {uwb_array: {array_side_m: 0.5}}}"));
  EXPECT_NE(error.find("robots[1].facts: uwb_array.array_side_m: a fact of the whole scenario"), std::string::npos) << error;
}

TEST(RangeAccelBoundFact, DeclaredOrTheDefaultSaidAsSuch) {
  RangeAccelBound bound = range_accel_bound(scenario_with(""));
  EXPECT_FALSE(bound.declared);
  EXPECT_EQ(bound.mps2, 2.2);
  EXPECT_NE(bound.key.find("default"), std::string::npos) << bound.key;
  bound = range_accel_bound(scenario_with("facts:\n  range_accel_bound_mps2: 3.5\n"));
  EXPECT_TRUE(bound.declared);
  EXPECT_EQ(bound.mps2, 3.5);
  EXPECT_EQ(bound.key, write_test_file("s.yaml", "").substr(0) + ": facts.range_accel_bound_mps2");
}

TEST(RangeAccelBoundFact, ANonPositiveOrNonNumericBoundOrAMapIsRefused) {
  std::string error = facts_error(scenario_with("facts:\n  range_accel_bound_mps2: 0\n"));
  EXPECT_NE(error.find("s.yaml: facts: range_accel_bound_mps2: must be > 0"), std::string::npos) << error;
  error = facts_error(scenario_with("facts:\n  range_accel_bound_mps2: high\n"));
  EXPECT_NE(error.find("range_accel_bound_mps2: expected a number, got 'high'"), std::string::npos) << error;
  error = facts_error(scenario_with("facts:\n  range_accel_bound_mps2: {value: 2}\n"));
  EXPECT_NE(error.find("range_accel_bound_mps2: expected a number, not a map"), std::string::npos) << error;
}

TEST(RobotFacts, RegisteredAsAScenarioCheck) {
  ComponentRegistry registry;
  register_system_checks(registry);
  EXPECT_THROW(registry.check_scenario(scenario_with("facts:\n  robot_body: {wheel_base_m: 0}\n")), ConfigError);
  EXPECT_NO_THROW(registry.check_scenario(scenario_with("")));
}

}  // namespace
}  // namespace robodds::system
