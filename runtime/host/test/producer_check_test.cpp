// One producer per topic instance, checked before anything runs (runtime/host/producer_check.hpp),
// and the scenario's standby_for validation.
#include "runtime/host/producer_check.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <vector>

#include "common/number_text.hpp"
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

// ---- input rate assumptions (issue 27) ---------------------------------------------------

/// Publishes sensor/range at `hz` (its parameter rate_hz), as range_sensor does.
class RangeAt : public Component {
 public:
  explicit RangeAt(double hz) : hz_(hz) {}
  void configure(ComponentContext& ctx) override {
    ctx.set_rate_hz(hz_, "rate_hz");
    ctx.advertise<idl::RangeMeasurement>("sensor/range");
  }
  void on_step(const StepInfo&) override {}

 private:
  double hz_;
};

/// Runs at `hz` and declares `assumption` on sensor/range (the key and kind it names).
class RangeReader : public Component {
 public:
  RangeReader(double hz, InputRateAssumption assumption) : hz_(hz), a_(std::move(assumption)) {}
  void configure(ComponentContext& ctx) override {
    ctx.set_rate_hz(hz_, "rate_hz");
    if (a_.kind == InputRateAssumption::Kind::kAgeLimit) {
      ctx.limits_age_of("sensor/range", a_.key, a_.value_s, a_.realtime_only, a_.robots);
    } else {
      ctx.expects_rate_of("sensor/range", a_.key, a_.kind, a_.robots);
    }
  }
  void on_step(const StepInfo&) override {}

 private:
  double hz_;
  InputRateAssumption a_;
};

InputRateAssumption assumption(InputRateAssumption::Kind kind, const std::string& key, double value_s = 0.0,
                               bool realtime_only = false, std::vector<std::uint32_t> robots = {}) {
  InputRateAssumption a;
  a.kind = kind;
  a.key = key;
  a.value_s = value_s;
  a.realtime_only = realtime_only;
  a.robots = std::move(robots);
  return a;
}

ComponentRegistry rate_registry() {
  using Kind = InputRateAssumption::Kind;
  ComponentRegistry registry;
  const auto no_params = [] { return params::ParamDoc{}; };
  for (double hz : {1.0, 2.0, 2.5, 5.0, 10.0, 50.0, 100.0}) {
    registry.add({"range_" + shortest_text(hz * 10) + "dhz", "sensor/range", "none",
                  [hz] { return std::make_unique<RangeAt>(hz); }, no_params, nullptr});
  }
  registry.add({"observer", "same rate", "none",
                [] { return std::make_unique<RangeReader>(50.0, assumption(Kind::kSameRate, "rate_hz")); },
                no_params, nullptr});
  registry.add({"epochs", "at least", "none",
                [] { return std::make_unique<RangeReader>(10.0, assumption(Kind::kAtLeastMyRate, "rate_hz")); },
                no_params, nullptr});
  registry.add({"watcher", "age limit, real time", "none",
                [] {
                  return std::make_unique<RangeReader>(100.0, assumption(Kind::kAgeLimit, "timeout_s", 0.5, true));
                },
                no_params, nullptr});
  registry.add({"always_watcher", "age limit, always", "none",
                [] {
                  return std::make_unique<RangeReader>(100.0, assumption(Kind::kAgeLimit, "timeout_s", 0.5, false));
                },
                no_params, nullptr});
  registry.add({"team_watcher", "age limit of robot 2's samples", "none",
                [] {
                  return std::make_unique<RangeReader>(
                      100.0, assumption(Kind::kAgeLimit, "timeout_s", 0.5, true, {2}));
                },
                no_params, nullptr});
  return registry;
}

/// check_input_rates() of `components` ("  - {...}" lines): the ConfigError's text ("" if none)
/// and the warnings.
struct RateCheck {
  std::string error;
  std::vector<std::string> warnings;
};
RateCheck rate_check(const std::string& components, TimeMode mode) {
  const Scenario scenario = load_scenario(write_test_file("rates.yaml", scenario_text(components)));
  RateCheck out;
  try {
    out.warnings = check_input_rates(scenario, scenario_component_topics(rate_registry(), scenario, mode), mode);
  } catch (const ConfigError& e) {
    out.error = e.what();
  }
  return out;
}

TEST(InputRates, ASlowerSensorThanASameRateConsumerIsAnErrorNamingFileKeysAndBothRates) {
  // Issue 27: a range sensor at 10 Hz feeding an observer configured for 50 Hz was accepted silently.
  const RateCheck c = rate_check("  - {name: ranger, type: range_100dhz}\n  - {name: obs, type: observer}\n", TimeMode::kLockstep);
  EXPECT_NE(c.error.find("rates.yaml: obs.rate_hz: obs runs at 50 Hz and assumes sensor/range at that rate, but its producer "
                         "'ranger' samples sensor/range at 10 Hz (ranger.rate_hz): 4 of its steps in 5 have no new sample and "
                         "would pass the last one on as new; give both the same rate"),
            std::string::npos)
      << c.error;
}

TEST(InputRates, TheSameRateIsSilentAndAFasterSensorAWarning) {
  const RateCheck same = rate_check("  - {name: ranger, type: range_500dhz}\n  - {name: obs, type: observer}\n", TimeMode::kRealtime);
  EXPECT_EQ(same.error, "");
  EXPECT_TRUE(same.warnings.empty()) << same.warnings.front();
  const RateCheck faster = rate_check("  - {name: ranger, type: range_1000dhz}\n  - {name: obs, type: observer}\n", TimeMode::kLockstep);
  EXPECT_EQ(faster.error, "");
  ASSERT_EQ(faster.warnings.size(), 1u);
  EXPECT_NE(faster.warnings[0].find("obs.rate_hz: obs runs at 50 Hz and assumes sensor/range at that rate, but its producer "
                                    "'ranger' samples sensor/range at 100 Hz (ranger.rate_hz): it takes several samples per step"),
            std::string::npos)
      << faster.warnings[0];
}

TEST(InputRates, ASlowerSensorThanAnAtLeastConsumerIsAWarning) {
  const RateCheck slower = rate_check("  - {name: ranger, type: range_50dhz}\n  - {name: est, type: epochs}\n", TimeMode::kRealtime);
  EXPECT_EQ(slower.error, "");
  ASSERT_EQ(slower.warnings.size(), 1u);
  EXPECT_NE(slower.warnings[0].find("est.rate_hz: est runs at 10 Hz and assumes sensor/range at least at that rate, but its "
                                    "producer 'ranger' samples sensor/range at 5 Hz (ranger.rate_hz): 1 of its steps in 2 have "
                                    "no new sample"),
            std::string::npos)
      << slower.warnings[0];
  EXPECT_TRUE(rate_check("  - {name: ranger, type: range_500dhz}\n  - {name: est, type: epochs}\n", TimeMode::kRealtime)
                  .warnings.empty());
}

TEST(InputRates, AnAgeLimitNotLongerThanTheProducersPeriodIsAnErrorWhereItApplies) {
  const std::string one_hz = "  - {name: ranger, type: range_10dhz}\n  - {name: w, type: watcher}\n";
  const RateCheck realtime = rate_check(one_hz, TimeMode::kRealtime);
  EXPECT_NE(realtime.error.find("rates.yaml: w.timeout_s: 0.5 s judges sensor/range stale, but its producer "
                                "'ranger' samples sensor/range at 1 Hz (ranger.rate_hz), one every 1 s: the input would be "
                                "stale between any two samples (raise timeout_s to 2 s or more, or the producer's rate)"),
            std::string::npos)
      << realtime.error;
  // A real-time limit in lockstep: said, not refused.
  const RateCheck lockstep = rate_check(one_hz, TimeMode::kLockstep);
  EXPECT_EQ(lockstep.error, "");
  ASSERT_EQ(lockstep.warnings.size(), 1u);
  EXPECT_NE(lockstep.warnings[0].find("; real time only: this lockstep run is not affected"), std::string::npos) << lockstep.warnings[0];
  // A limit that applies always is refused in lockstep too; exactly one period is not longer than it.
  EXPECT_NE(rate_check("  - {name: ranger, type: range_20dhz}\n  - {name: w, type: always_watcher}\n", TimeMode::kLockstep)
                .error.find("w.timeout_s: 0.5 s judges sensor/range stale"),
            std::string::npos);
}

TEST(InputRates, AnAgeLimitShorterThanTwoPeriodsIsAWarningAndLongerIsSilent) {
  const RateCheck c = rate_check("  - {name: ranger, type: range_25dhz}\n  - {name: w, type: watcher}\n", TimeMode::kRealtime);
  EXPECT_EQ(c.error, "");
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("w.timeout_s: 0.5 s judges sensor/range stale, less than two of its producer's periods: its "
                               "producer 'ranger' samples sensor/range at 2.5 Hz (ranger.rate_hz), so one lost sample makes it stale"),
            std::string::npos)
      << c.warnings[0];
  const RateCheck ok = rate_check("  - {name: ranger, type: range_100dhz}\n  - {name: w, type: watcher}\n", TimeMode::kRealtime);
  EXPECT_EQ(ok.error, "");
  EXPECT_TRUE(ok.warnings.empty());
}

TEST(InputRates, OnlyProducersOfTheRobotsReadAreJudged) {
  // The 1 Hz sensor serves robot 1 only; the watcher reads robot 2's samples (from the 10 Hz one).
  const std::string components = "  - {name: slow, type: range_10dhz, robots: [1]}\n  - {name: fast, type: range_100dhz, robots: [2]}\n"
                                 "  - {name: w, type: team_watcher, robots: [1]}\n";
  EXPECT_EQ(rate_check(components, TimeMode::kRealtime).error, "");
  // Reading its own robot (1): the slow one is its producer.
  EXPECT_NE(rate_check("  - {name: slow, type: range_10dhz, robots: [1]}\n  - {name: fast, type: range_100dhz, robots: [2]}\n"
                       "  - {name: w, type: watcher, robots: [1]}\n",
                       TimeMode::kRealtime)
                .error.find("'slow'"),
            std::string::npos);
}

}  // namespace
}  // namespace robodds
