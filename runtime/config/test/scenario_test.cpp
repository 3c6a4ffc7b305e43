#include "runtime/config/scenario.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "runtime/base/error.hpp"
#include "tests/support/temp_file.hpp"

namespace robodds {
namespace {

using test_support::write_test_file;

std::string load_error(const std::string& text) {
  const std::string path = write_test_file("scenario.yaml", text);
  try {
    load_scenario(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

const char* kValid = R"(name: s
step_s: 0.01
duration_s: 1.0
seed: 3
robots:
  - {id: 1, x: 1, y: 2, theta: 0.5}
  - {id: 2}
components:
  - {name: plant, robots: [1, 2], params: {wheel_base_m: 0.4}}
  - {name: position_sensor}
groups:
  sim: [plant]
)";

TEST(Scenario, LoadsValidFile) {
  const Scenario s = load_scenario(write_test_file("ok.yaml", kValid));
  EXPECT_EQ(s.name, "s");
  EXPECT_EQ(s.last_step(), 100u);
  ASSERT_EQ(s.robots.size(), 2u);
  EXPECT_DOUBLE_EQ(s.robot(1).theta, 0.5);
  EXPECT_EQ(s.component("plant").type, "plant");
  EXPECT_EQ(s.component("plant").overrides.at("wheel_base_m").yaml, "0.4");
  ASSERT_EQ(s.groups.size(), 2u);  // position_sensor gets a group of its own
  EXPECT_EQ(s.group("position_sensor").components.front(), "position_sensor");
}

TEST(Scenario, RobotsServedCountsDistinctRobotsOfTheNamedComponents) {
  const Scenario s = load_scenario(write_test_file("served.yaml", R"(name: s
step_s: 0.01
duration_s: 1.0
seed: 1
robots: [{id: 1}, {id: 2}, {id: 3}]
components:
  - {name: plant}
  - {name: control1, type: open_loop_commander, robots: [1]}
  - {name: control2, type: open_loop_commander, robots: [1, 2]}
)"));
  EXPECT_EQ(s.robots_served_by({"plant"}), 3u) << "default: every robot";
  EXPECT_EQ(s.robots_served_by({"control1", "control2"}), 2u);
  EXPECT_EQ(s.robots_served_by({}), 0u);
  EXPECT_THROW(s.robots_served_by({"nobody"}), ConfigError);
}

TEST(Scenario, UnknownRobotIsNamed) {
  std::string text = kValid;
  text.replace(text.find("robots: [1, 2]"), 14, "robots: [1, 7]");
  const std::string message = load_error(text);
  EXPECT_NE(message.find("components[0].robots[1]: unknown robot 7"), std::string::npos) << message;
}

TEST(Scenario, UnknownGroupMemberIsNamed) {
  std::string text = kValid;
  text.replace(text.find("sim: [plant]"), 12, "sim: [plantt]");
  EXPECT_NE(load_error(text).find("groups.sim: unknown component 'plantt'; did you mean 'plant'?"), std::string::npos);
}

TEST(Scenario, AnUnknownComponentOrGroupNameNamesTheClosest) {
  const Scenario s = load_scenario(write_test_file("ok.yaml", kValid));
  std::string message;
  try {
    s.group("sin");
  } catch (const ConfigError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("groups: no group named 'sin'; did you mean 'sim'? (groups: "), std::string::npos) << message;
  try {
    s.component("plnat");
  } catch (const ConfigError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("components: no component named 'plnat'; did you mean 'plant'?"), std::string::npos) << message;
}

TEST(Scenario, BadValuesAreNamed) {
  std::string text = kValid;
  text.replace(text.find("step_s: 0.01"), 12, "step_s: -1");
  EXPECT_NE(load_error(text).find("step_s: must be > 0"), std::string::npos);
  std::string typo = kValid;
  typo.replace(typo.find("seed: 3"), 7, "sed: 3");
  EXPECT_NE(load_error(typo).find("sed: unknown key"), std::string::npos);
}

TEST(Scenario, DuplicateRobotIsRejected) {
  std::string text = kValid;
  text.replace(text.find("{id: 2}"), 7, "{id: 1}");
  EXPECT_NE(load_error(text).find("duplicate robot id 1"), std::string::npos);
}

// A top-level section the runtime does not know is an error, unless the layer above registered it
// (system/mission_plan.cpp registers targets and events); the runtime stores it unread.
TEST(Scenario, UnknownTopLevelKeysAreErrorsUnlessRegisteredAsSections) {
  EXPECT_NE(load_error(std::string(kValid) + "durations_s: 3\n").find("durations_s: unknown key; did you mean 'duration_s'? (known: name,"),
            std::string::npos);
  register_scenario_section("test_section");
  const Scenario s = load_scenario(write_test_file("section.yaml", std::string(kValid) + "test_section: [{a: 1}, {a: 2}]\n"));
  ASSERT_EQ(s.sections.count("test_section"), 1u);
  EXPECT_EQ(s.sections.at("test_section").yaml, "[{a: 1}, {a: 2}]");
  EXPECT_NE(load_error(std::string(kValid) + "durations_s: 3\n").find("test_section"), std::string::npos)
      << "the known keys name the registered sections";
}

TEST(Scenario, MissingFileIsNamed) {
  try {
    load_scenario("/nonexistent/s.yaml");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/s.yaml: cannot open"), std::string::npos);
  }
}

TEST(Scenario, DirectoryIsNamed) {
  const std::string dir = ::testing::TempDir();
  try {
    load_scenario(dir);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), dir + ": is a directory, not a scenario file");
  }
}

TEST(Scenario, StepCountThatDoesNotFitIsNamed) {
  std::string text = kValid;
  text.replace(text.find("step_s: 0.01"), 12, "step_s: 1e-25");
  EXPECT_NE(load_error(text).find(": step_s: duration 1 s at step 1e-25 s is 1e+25 steps, more than 1099511627776 (2^40)"),
            std::string::npos)
      << load_error(text);
  std::string small = kValid;
  small.replace(small.find("step_s: 0.01"), 12, "step_s: 1e-18");
  EXPECT_NE(load_error(small).find("is 1e+18 steps, more than 1099511627776"), std::string::npos) << load_error(small);
}

TEST(CheckedLastStep, RoundsTheQuotient) {
  EXPECT_EQ(checked_last_step(0.01, 1.0, "f", "k"), 100u);
  EXPECT_EQ(checked_last_step(0.01, 0.004, "f", "k"), 0u);
  EXPECT_EQ(checked_last_step(1.0, static_cast<double>(kMaxLastStep), "f", "k"), kMaxLastStep);
}

TEST(CheckedLastStep, TooManyStepsNonFiniteAndNonPositiveAreConfigErrorsNamingFileAndKey) {
  const auto error = [](double step, double duration) {
    try {
      checked_last_step(step, duration, "s.yaml", "step_s");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error(1.0, static_cast<double>(kMaxLastStep) + 1.0),
            "s.yaml: step_s: duration 1099511627777 s at step 1 s is 1.1e+12 steps, more than 1099511627776 (2^40); use a "
            "longer step or a shorter duration");
  EXPECT_NE(error(1e-25, 20.0).find("is 2e+26 steps"), std::string::npos);
  EXPECT_NE(error(1e-300, 1e300).find("is inf steps"), std::string::npos);  // the quotient overflows a double
  EXPECT_EQ(error(std::nan(""), 1.0), "s.yaml: step_s: the step must be a positive, finite number of seconds (got nan)");
  EXPECT_EQ(error(0.0, 1.0), "s.yaml: step_s: the step must be a positive, finite number of seconds (got 0)");
  EXPECT_EQ(error(0.01, std::nan("")), "s.yaml: step_s: the duration must be a positive, finite number of seconds (got nan)");
  EXPECT_EQ(error(0.01, -5.0), "s.yaml: step_s: the duration must be a positive, finite number of seconds (got -5)");
  EXPECT_NE(error(0.01, HUGE_VAL).find("(got inf)"), std::string::npos);
}

TEST(ApplyRunOverrides, SetsDurationAndSeedOrKeepsTheScenarios) {
  Scenario s = load_scenario(write_test_file("ok.yaml", kValid));
  apply_run_overrides(s, std::nullopt, std::nullopt);
  EXPECT_EQ(s.duration_s, 1.0);
  EXPECT_EQ(s.seed, 3u);
  apply_run_overrides(s, 2.5, std::uint64_t{0});
  EXPECT_EQ(s.duration_s, 2.5);
  EXPECT_EQ(s.seed, 0u);
  EXPECT_EQ(s.last_step(), 250u);
}

TEST(ApplyRunOverrides, ADurationGivingTooManyStepsNamesTheOptionAndKeepsTheScenario) {
  Scenario s = load_scenario(write_test_file("ok.yaml", kValid));
  try {
    apply_run_overrides(s, 1e300, std::nullopt);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--duration: duration 1e+300 s at step 0.01 s is 1e+302 steps", 0), 0u) << e.what();
  }
  EXPECT_EQ(s.duration_s, 1.0);
}

}  // namespace
}  // namespace robodds

namespace robodds {
namespace {

TEST(ApplyParamOverrides, PutsOverridesOnTopOfTheScenarios) {
  Scenario s = load_scenario(test_support::write_test_file("ok.yaml", kValid));
  const std::string file = test_support::write_test_file("over.yaml", "plant:\n  wheel_base_m: 0.5\n  gains: {kd: 2}\n");
  apply_param_overrides(s, load_param_file(file), file);
  const ComponentSpec& plant = s.component("plant");
  ASSERT_EQ(plant.overrides.count("wheel_base_m"), 1u);
  EXPECT_EQ(plant.overrides.at("wheel_base_m").yaml, "0.5");
  EXPECT_EQ(plant.overrides.at("wheel_base_m").file, file);
  ASSERT_EQ(plant.overrides.count("gains.kd"), 1u);
  EXPECT_EQ(plant.overrides.at("gains.kd").yaml, "2");
  EXPECT_TRUE(s.component("position_sensor").overrides.empty());
}

TEST(ApplyParamOverrides, UnknownComponentIsNamedWithTheFile) {
  Scenario s = load_scenario(test_support::write_test_file("ok.yaml", kValid));
  const std::string file = test_support::write_test_file("over.yaml", "controller:\n  gain: 1\n");
  try {
    apply_param_overrides(s, load_param_file(file), file);
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("controller.gain"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("expected <component>.<parameter> of a scenario component: no component 'controller' in " +
                                         s.file + " (components: "),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace robodds
