// One producer per topic instance, checked before anything runs (runtime/host/producer_check.hpp),
// and the scenario's standby_for validation.
#include "runtime/host/producer_check.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <vector>

#include "runtime/base/error.hpp"
#include "runtime/bus/memory_bus.hpp"
#include "tests/support/temp_file.hpp"

namespace robodds {
namespace {

using test_support::write_test_file;

/// Publishes plant/cmd (commander) or estimate/pose (estimator), like the real components.
class Commander : public Component {
 public:
  void configure(ComponentContext& ctx) override { ctx.advertise<idl::VelocityCommand>("plant/cmd"); }
  void on_step(const StepInfo&) override {}
};
class Estimator : public Component {
 public:
  void configure(ComponentContext& ctx) override { ctx.advertise<idl::PoseEstimate>("estimate/pose"); }
  void on_step(const StepInfo&) override {}
};

/// Publishes sensor/uwb (key robot_id, peer_id) for (each of its robots, each other robot), and
/// declares those pairs, as uwb_sensor does.
class Ranger : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    ctx.advertise<idl::UwbRanges>("sensor/uwb");
    std::vector<std::uint64_t> keys;
    for (const RobotSpec& robot : ctx.robots()) {
      for (const RobotSpec& peer : ctx.scenario().robots) {
        if (peer.id != robot.id) {
          keys.push_back((std::uint64_t{robot.id} << 32) | peer.id);
        }
      }
    }
    ctx.publishes_instances("sensor/uwb", keys);
  }
  void on_step(const StepInfo&) override {}
};

ComponentRegistry test_registry() {
  ComponentRegistry registry;
  const auto no_params = [] { return params::ParamDoc{}; };
  registry.add({"commander", "plant/cmd", "none", [] { return std::make_unique<Commander>(); }, no_params, nullptr});
  registry.add({"estimator", "estimate/pose", "none", [] { return std::make_unique<Estimator>(); }, no_params, nullptr});
  registry.add({"ranger", "sensor/uwb", "none", [] { return std::make_unique<Ranger>(); }, no_params, nullptr});
  return registry;
}

std::string scenario_text(const std::string& components, const std::string& groups = "") {
  return "name: s\nstep_s: 0.01\nduration_s: 1.0\nseed: 1\nrobots:\n  - {id: 1}\n  - {id: 2}\ncomponents:\n" + components +
         (groups.empty() ? "" : "groups:\n" + groups);
}

std::string producer_error(const std::string& components) {
  const Scenario scenario = load_scenario(write_test_file("producers.yaml", scenario_text(components)));
  try {
    check_one_producer_per_instance(scenario, scenario_producers(test_registry(), scenario, TimeMode::kLockstep));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioProducers, DryConfigureRecordsTheAdvertisedTopics) {
  const Scenario scenario = load_scenario(write_test_file(
      "p.yaml", scenario_text("  - {name: a, type: commander}\n  - {name: e, type: estimator}\n")));
  const ScenarioProducers producers = scenario_producers(test_registry(), scenario, TimeMode::kLockstep);
  EXPECT_EQ(producers.at("a"), std::set<std::string>{"plant/cmd"});
  EXPECT_EQ(producers.at("e"), std::set<std::string>{"estimate/pose"});
}

TEST(ProducedInstances, AreThePairsTheProducersDeclareInKeyOrder) {
  const Scenario scenario = load_scenario(write_test_file(
      "pairs.yaml", scenario_text("  - {name: r2, type: ranger, robots: [2]}\n  - {name: r1, type: ranger, robots: [1]}\n"
                                  "  - {name: a, type: commander}\n")));
  const ScenarioProducers producers = scenario_producers(test_registry(), scenario, TimeMode::kRealtime);
  const ProducedInstances instances = produced_instances(test_registry(), scenario, producers, TimeMode::kRealtime);
  ASSERT_EQ(instances.size(), 1u) << "plant/cmd's instances are its robots: nothing declared";
  EXPECT_EQ(instances.at("sensor/uwb"), (std::vector<std::uint64_t>{(1ull << 32) | 2, (2ull << 32) | 1}));
}

TEST(OneProducerPerInstance, TwoCommandersOfOneRobotAreOneErrorNamingFileTopicInstanceAndBoth) {
  const std::string error = producer_error(
      "  - {name: first_commander, type: commander, robots: [1, 2]}\n  - {name: second_commander, type: commander, robots: [2]}\n");
  EXPECT_NE(error.find("producers.yaml"), std::string::npos) << error;
  EXPECT_NE(error.find("plant/cmd"), std::string::npos) << error;
  EXPECT_NE(error.find("robot_id=2"), std::string::npos) << error;
  EXPECT_NE(error.find("'first_commander'"), std::string::npos) << error;
  EXPECT_NE(error.find("'second_commander'"), std::string::npos) << error;
}

TEST(OneProducerPerInstance, OneCommanderPerRobotAndAStandbyAreAccepted) {
  EXPECT_EQ(producer_error("  - {name: a, type: commander, robots: [1]}\n  - {name: b, type: commander, robots: [2]}\n"), "");
  EXPECT_EQ(producer_error("  - {name: e, type: estimator}\n  - {name: e_standby, type: estimator, standby_for: e}\n"), "");
}

TEST(ExclusiveTopics, AreTheTopicsOfStandbysWithTheStandbysWritersWeaker) {
  const Scenario scenario = load_scenario(write_test_file(
      "standby.yaml", scenario_text("  - {name: a, type: commander}\n  - {name: e, type: estimator}\n"
                                    "  - {name: e_standby, type: estimator, standby_for: e}\n")));
  const ScenarioProducers producers = scenario_producers(test_registry(), scenario, TimeMode::kRealtime);
  const std::set<std::string> exclusive = exclusive_topics(scenario, producers);
  EXPECT_EQ(exclusive, std::set<std::string>{"estimate/pose"});

  struct OwnershipBus : MemoryBus {
    void set_exclusive_ownership(const std::string& topic, std::uint32_t strength) override { strengths[topic] = strength; }
    std::map<std::string, std::uint32_t> strengths;
  };
  OwnershipBus primary_host;
  apply_exclusive_ownership(primary_host, scenario, producers, exclusive, {"e", "a"});
  EXPECT_EQ(primary_host.strengths, (std::map<std::string, std::uint32_t>{{"estimate/pose", kPrimaryStrength}}));
  OwnershipBus standby_host;
  apply_exclusive_ownership(standby_host, scenario, producers, exclusive, {"e_standby"});
  EXPECT_EQ(standby_host.strengths, (std::map<std::string, std::uint32_t>{{"estimate/pose", kStandbyStrength}}));
  EXPECT_LT(kStandbyStrength, kPrimaryStrength);
}

std::string load_error(const std::string& text) {
  try {
    load_scenario(write_test_file("standby.yaml", text));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Standby, MustNameAPrimaryOfTheSameTypeAndRobotsInAnotherGroup) {
  EXPECT_NE(load_error(scenario_text("  - {name: s, type: estimator, standby_for: nobody}\n")).find("unknown component 'nobody'"),
            std::string::npos);
  EXPECT_NE(load_error(scenario_text("  - {name: e, type: estimator}\n  - {name: s, type: commander, standby_for: e}\n"))
                .find("its primary's type"),
            std::string::npos);
  EXPECT_NE(load_error(scenario_text("  - {name: e, type: estimator, robots: [1]}\n"
                                     "  - {name: s, type: estimator, standby_for: e}\n"))
                .find("other robots"),
            std::string::npos);
  EXPECT_NE(load_error(scenario_text("  - {name: e, type: estimator}\n  - {name: s, type: estimator, standby_for: e}\n",
                                     "  g: [e, s]\n"))
                .find("in group 'g' with its primary"),
            std::string::npos);
  EXPECT_NE(load_error(scenario_text("  - {name: e, type: estimator}\n  - {name: s, type: estimator, standby_for: e}\n"
                                     "  - {name: t, type: estimator, standby_for: s}\n"))
                .find("itself a standby"),
            std::string::npos);
}

TEST(Standby, RunsOnlyInRealTimeWithOneProcessPerGroup) {
  const Scenario scenario = load_scenario(write_test_file(
      "standby.yaml", scenario_text("  - {name: e, type: estimator}\n  - {name: s, type: estimator, standby_for: e}\n")));
  EXPECT_THROW(check_standby_deployment(scenario, TimeMode::kLockstep, false), ConfigError);
  EXPECT_THROW(check_standby_deployment(scenario, TimeMode::kRealtime, true), ConfigError);
  EXPECT_NO_THROW(check_standby_deployment(scenario, TimeMode::kRealtime, false));
  // One host given both (robodds host --components e,s) would die with its primary.
  EXPECT_THROW(check_standby_apart(scenario, {"e", "s"}), ConfigError);
  EXPECT_NO_THROW(check_standby_apart(scenario, {"s"}));
}

}  // namespace
}  // namespace robodds
