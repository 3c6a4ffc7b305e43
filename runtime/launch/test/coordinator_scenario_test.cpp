#include "runtime/launch/coordinator_scenario.hpp"

#include <gtest/gtest.h>

#include "runtime/base/error.hpp"

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

HostArgs coordinator_args() {
  HostArgs args;
  args.coordinate = true;
  args.members = {"sim", "sensing"};
  args.duration_s = 0.5;
  return args;
}

TEST(CoordinatorScenario, StepDurationAndNoComponents) {
  HostArgs args = coordinator_args();
  Scenario s = coordinator_scenario(args);
  EXPECT_EQ(s.step_s, kStandaloneStepS);  // the component executables' default: the ticks must agree with it
  EXPECT_EQ(s.duration_s, 0.5);
  EXPECT_EQ(s.last_step(), 50u);
  EXPECT_TRUE(s.components.empty());
  EXPECT_TRUE(s.groups.empty());
  EXPECT_TRUE(s.robots.empty());
  args.step_s = 0.02;
  args.duration_s = 60.0;
  s = coordinator_scenario(args);
  EXPECT_EQ(s.step_s, 0.02);
  EXPECT_EQ(s.last_step(), 3000u);
}

TEST(CoordinatorScenario, DurationIsRequiredAndTheStepCountChecked) {
  HostArgs args = coordinator_args();
  args.duration_s.reset();
  EXPECT_EQ(config_error([&] { coordinator_scenario(args); }),
            "--duration is required without a scenario: the coordinator ends the run there (s)");
  args.duration_s = 1e300;
  EXPECT_NE(config_error([&] { coordinator_scenario(args); }).find("--duration"), std::string::npos);
}

TEST(CoordinatorScenario, ComponentOptionsAreRefused) {
  HostArgs args = coordinator_args();
  args.robots = {"1"};
  EXPECT_NE(config_error([&] { coordinator_scenario(args); }).find("belong to the component executables"), std::string::npos);
}

TEST(CoordinatorScenario, SplitMembersKeepsEmptyNames) {
  EXPECT_EQ(split_members("plant,pf_estimator"), (std::vector<std::string>{"plant", "pf_estimator"}));
  EXPECT_EQ(split_members("sim,,x"), (std::vector<std::string>{"sim", "", "x"}));
  EXPECT_EQ(split_members("sim,"), (std::vector<std::string>{"sim", ""}));
  EXPECT_EQ(split_members(","), (std::vector<std::string>{"", ""}));
  EXPECT_TRUE(split_members("").empty());
}

TEST(CoordinatorScenario, MembersMustBeGivenNonEmptyAndOnce) {
  EXPECT_NE(config_error([] { check_members({}); }).find("--members: give the members to wait for"), std::string::npos);
  EXPECT_EQ(config_error([] { check_members({"sim", "", "sensing"}); }), "--members 'sim,,sensing': member 2 is empty");
  EXPECT_EQ(config_error([] { check_members({"sim", "sensing", "sim"}); }), "--members 'sim,sensing,sim': 'sim' is given twice");
  const std::string long_name(kMaxMemberLength + 1, 'x');
  EXPECT_EQ(config_error([&] { check_members({long_name}); }),
            "--members '" + long_name + "': '" + long_name + "' is longer than 64 characters");
  EXPECT_EQ(config_error([] { check_members({"plant", "pf estimator", "x"}); }), "");  // names are free
  EXPECT_EQ(config_error([&] { check_members({std::string(kMaxMemberLength, 'y')}); }), "");
}

}  // namespace
}  // namespace robodds
