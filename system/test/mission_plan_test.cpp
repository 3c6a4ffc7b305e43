#include "system/mission_plan.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "runtime/base/error.hpp"
#include "tests/support/temp_file.hpp"

namespace robodds::system {
namespace {

using test_support::write_test_file;

const char* kValid = R"(name: s
step_s: 0.01
duration_s: 1.0
seed: 3
robots:
  - {id: 1, x: 1, y: 2, theta: 0.5}
  - {id: 2}
components:
  - {name: plant, robots: [1, 2]}
)";

std::string load_error(const std::string& text) {
  try {
    target_plan(load_scenario(write_test_file("scenario.yaml", text)));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

const char* kTargets = R"(targets:
  - {id: 1, x: 10, y: 20, radius_m: 5}
  - {id: 2, x: 30, y: 40, radius_m: 6}
)";

TEST(MissionPlan, LoadsTargetsAndEvents) {
  const std::string text = std::string(kValid) + kTargets +
                           "events:\n  - {time_s: 0, robots: [1, 2], target: 1}\n"
                           "  - {time_s: 0.5, robots: [2], leave: true}\n";
  const model::TargetPlan plan = target_plan(load_scenario(write_test_file("events.yaml", text)));
  ASSERT_EQ(plan.targets.size(), 2u);
  EXPECT_DOUBLE_EQ(plan.targets[1].radius_m, 6.0);
  ASSERT_EQ(plan.events.size(), 2u);
  EXPECT_TRUE(plan.events[1].leave);
  EXPECT_EQ(plan.events[0].robots, (std::vector<std::uint32_t>{1, 2}));
}

// Each bad mission is a ConfigError naming the key and the reason.
TEST(MissionPlan, BadTargetsAndEventsAreNamed) {
  const auto error_of = [](const std::string& targets, const std::string& events) {
    return load_error(std::string(kValid) + targets + "events:\n" + events);
  };
  EXPECT_NE(error_of(kTargets, "  - {time_s: 0, robots: [3], target: 1}\n").find("events[0].robots[0]: unknown robot 3"),
            std::string::npos);
  EXPECT_NE(error_of(kTargets, "  - {time_s: 1.5, robots: [1], target: 1}\n").find("events[0].time_s: 1.5 s is outside the run"),
            std::string::npos);
  EXPECT_NE(error_of(kTargets, "  - {time_s: 0, robots: [1], target: 9}\n").find("events[0].target: unknown target 9"),
            std::string::npos);
  EXPECT_NE(error_of(kTargets, "  - {time_s: 0, robots: [1]}\n").find("events[0]: give either"), std::string::npos);
  EXPECT_NE(error_of(kTargets, "  - {time_s: 0.5, robots: [1], target: 1}\n  - {time_s: 0.2, robots: [1], target: 2}\n")
                .find("events[1].time_s: 0.2 s is before the previous event's 0.5 s"),
            std::string::npos);
  EXPECT_NE(error_of(kTargets, "  - {time_s: 0, robots: [1], leave: true}\n  - {time_s: 0.2, robots: [1], target: 2}\n")
                .find("events[1].robots[0]: robot 1 left the mission"),
            std::string::npos);
  EXPECT_NE(error_of("targets:\n  - {id: 1, x: 0, y: 0, radius_m: 0}\n", "  - {time_s: 0, robots: [1], target: 1}\n")
                .find("targets[0].radius_m: must be > 0"),
            std::string::npos);
  EXPECT_NE(load_error(std::string(kValid) + "events:\n  - {time_s: 0, robots: [1], target: 1}\n").find("events: events assign targets"),
            std::string::npos);
}

TEST(MissionPlan, AScenarioWithoutTargetsHasAnEmptyPlan) {
  EXPECT_TRUE(target_plan(load_scenario(write_test_file("none.yaml", kValid))).empty());
}

}  // namespace
}  // namespace robodds::system
