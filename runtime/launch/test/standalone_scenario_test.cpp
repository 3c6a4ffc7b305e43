#include "runtime/launch/standalone_scenario.hpp"

#include <gtest/gtest.h>

#include "runtime/base/error.hpp"
#include "tests/support/temp_file.hpp"

namespace robodds {
namespace {

/// The message of the ConfigError that `f` throws ("" if it throws none).
template <class F>
std::string config_error(F&& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

HostArgs pf_args() {
  HostArgs args;
  args.type = "pf_estimator";
  args.robots = {"1", "7:50,10,-0.5"};
  return args;
}

TEST(StandaloneScenario, OneComponentInOneGroupWithTheDefaults) {
  const Scenario s = standalone_scenario(pf_args());
  ASSERT_EQ(s.components.size(), 1u);
  EXPECT_EQ(s.components[0].name, "pf_estimator");
  EXPECT_EQ(s.components[0].type, "pf_estimator");
  EXPECT_EQ(s.components[0].robots, (std::vector<std::uint32_t>{1, 7}));
  ASSERT_EQ(s.groups.size(), 1u);
  EXPECT_EQ(s.groups[0].name, "pf_estimator");
  EXPECT_EQ(s.groups[0].components, std::vector<std::string>{"pf_estimator"});
  EXPECT_EQ(s.step_s, kStandaloneStepS);
  EXPECT_EQ(s.duration_s, kUntilStoppedS);
  EXPECT_EQ(s.seed, 1u);
  ASSERT_EQ(s.robots.size(), 2u);
  EXPECT_EQ(s.robot(7).x, 50.0);
  EXPECT_EQ(s.robot(7).y, 10.0);
  EXPECT_EQ(s.robot(7).theta, -0.5);
  EXPECT_EQ(s.robot(1).x, 0.0);
}

TEST(StandaloneScenario, NameMemberStepSeedDurationAndParamsFromTheCommandLine) {
  HostArgs args = pf_args();
  args.name = "estimator";
  args.member = "estimation";
  args.step_s = 0.02;
  args.seed = 7;
  args.duration_s = 3.0;
  args.params = test_support::write_test_file("pf.yaml", "num_particles: 200\ninit_mode: uniform_area\n");
  const Scenario s = standalone_scenario(args);
  EXPECT_EQ(s.components[0].name, "estimator");
  EXPECT_EQ(s.groups[0].name, "estimation");
  EXPECT_EQ(s.step_s, 0.02);
  EXPECT_EQ(s.seed, 7u);
  EXPECT_EQ(s.duration_s, 3.0);
  ASSERT_EQ(s.components[0].overrides.count("num_particles"), 1u);
  EXPECT_EQ(s.components[0].overrides.at("num_particles").yaml, "200");
  EXPECT_EQ(s.components[0].overrides.at("num_particles").file, args.params);
}

// A component without a scenario takes the shared facts (the robot's body) from its --params
// file's `facts:`; they are not parameters of the component.
TEST(StandaloneScenario, TheParamsFilesFactsAreTheScenariosFacts) {
  HostArgs args = pf_args();
  args.params = test_support::write_test_file("plant.yaml", "command_timeout_s: 0.3\nfacts:\n  robot_body: {wheel_base_m: 0.3}\n");
  const Scenario s = standalone_scenario(args);
  ASSERT_EQ(s.facts.count("robot_body.wheel_base_m"), 1u);
  EXPECT_EQ(s.facts.at("robot_body.wheel_base_m").yaml, "0.3");
  EXPECT_EQ(s.facts.at("robot_body.wheel_base_m").file, args.params + ": facts");
  EXPECT_EQ(s.components[0].overrides.count("command_timeout_s"), 1u);
  EXPECT_EQ(s.components[0].overrides.size(), 1u);
}

TEST(StandaloneScenario, BadRobotsAreConfigErrorsNamingTheValue) {
  for (const char* bad : {"", "x", "-1", "1:", "1:2,3", "1:2,3,4,", "1:a,0,0", "1:0,0,nan", "99999999999"}) {
    HostArgs args = pf_args();
    args.robots = {bad};
    const std::string message = config_error([&] { standalone_scenario(args); });
    EXPECT_NE(message.find(std::string("--robot '") + bad + "'"), std::string::npos) << message;
  }
  HostArgs twice = pf_args();
  twice.robots = {"3", "3:1,1,1"};
  EXPECT_NE(config_error([&] { standalone_scenario(twice); }).find("robot 3 is given twice"),
            std::string::npos);
}

TEST(StandaloneScenario, NeedsRobotsAndAPositiveStep) {
  HostArgs none = pf_args();
  none.robots.clear();
  EXPECT_NE(config_error([&] { standalone_scenario(none); }).find("--robot ID"),
            std::string::npos);
  HostArgs zero_step = pf_args();
  zero_step.step_s = 0.0;
  EXPECT_NE(config_error([&] { standalone_scenario(zero_step); }).find("--step"),
            std::string::npos);
}

TEST(StandaloneScenario, StepCountMustFit) {
  HostArgs tiny = pf_args();
  tiny.step_s = 1e-25;
  tiny.duration_s = 10.0;
  EXPECT_EQ(config_error([&] { standalone_scenario(tiny); })
                .rfind("--step: duration 10 s at step 1e-25 s is 1e+26 steps", 0),
            0u)
      << config_error([&] { standalone_scenario(tiny); });
  // Until stopped (no --duration) is at most kMaxLastStep steps: a short step still runs.
  HostArgs until_stopped = pf_args();
  until_stopped.step_s = 1e-4;
  const Scenario s = standalone_scenario(until_stopped);
  EXPECT_EQ(s.last_step(), kMaxLastStep);
}

TEST(StandaloneScenario, MissingParamsFileIsNamed) {
  HostArgs args = pf_args();
  args.params = "/nonexistent/pf.yaml";
  EXPECT_NE(config_error([&] { standalone_scenario(args); }).find("/nonexistent/pf.yaml"),
            std::string::npos);
}

}  // namespace
}  // namespace robodds
