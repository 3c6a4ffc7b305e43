// The lockstep host loop through Host's public API (configure(), run()) on the in-memory bus:
// tick delivery and acknowledgement (also through the host's own in-memory bus), periods,
// delayed inputs, input timeouts, the lockstep window and failing components. Components are test scripts (runtime/testing/node_harness.hpp).
#include "runtime/host/host.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/testing/node_harness.hpp"
#include "runtime/topics/topic_catalog.hpp"

namespace robodds {
namespace {

using testing::NodeHarness;

// 11 steps (0..10), two robots, a producer and a consumer of plant/state.
const char* kScenario = R"(name: host_test
step_s: 0.01
duration_s: 0.1
seed: 1
robots:
  - {id: 1}
  - {id: 2}
components:
  - {name: producer, type: producer}
  - {name: consumer, type: consumer}
)";

/// Adds a "producer" type that publishes plant/state x = 100 * step + robot id for its robots.
void add_producer(NodeHarness& h) {
  auto out = std::make_shared<Output<idl::RobotState>*>(nullptr);
  auto keys = std::make_shared<std::vector<std::uint64_t>>();
  h.add_script("producer",
               [out, keys](ComponentContext& ctx) {
                 *out = &ctx.advertise<idl::RobotState>("plant/state");
                 *keys = ctx.robot_keys();
               },
               [out, keys](const StepInfo& info) {
                 for (std::uint64_t key : *keys) {
                   idl::RobotState s;
                   s.robot_id(static_cast<std::uint32_t>(key));
                   s.x(100.0 * static_cast<double>(info.step) + static_cast<double>(key));
                   (*out)->publish(s);
                 }
               });
}

/// What the consumer saw at each of its steps: robot 1's newest readable x (nullopt: none).
using Seen = std::map<std::uint64_t, std::optional<double>>;

/// Adds a "consumer" type reading plant/state with `subscription` and logging into *seen.
void add_consumer(NodeHarness& h, Subscription subscription, std::shared_ptr<Seen> seen, double rate_hz = 0.0) {
  auto input = std::make_shared<Input<idl::RobotState>*>(nullptr);
  h.add_script("consumer",
               [input, subscription, rate_hz](ComponentContext& ctx) {
                 *input = &ctx.subscribe<idl::RobotState>("plant/state", subscription);
                 if (rate_hz > 0.0) {
                   ctx.set_rate_hz(rate_hz, "rate_hz");
                 }
               },
               [input, seen](const StepInfo& info) {
                 const idl::RobotState* s = (*input)->latest(1);
                 (*seen)[info.step] = s == nullptr ? std::nullopt : std::optional<double>(s->x());
               });
}

TEST(HostLoop, EveryTickIsDeliveredRunAndAcknowledged) {
  NodeHarness h(kScenario);
  add_producer(h);
  auto seen = std::make_shared<Seen>();
  add_consumer(h, Subscription::instances({1, 2}), seen);
  const auto& ticks = h.record<idl::SimTick>("sim/clock");
  const auto& acks = h.record<idl::StepDone>("sim/step_done");
  const RunStats stats = h.run({"consumer", "producer"});  // the consumer is listed first: the gate orders them

  EXPECT_EQ(stats.steps, 11u);
  ASSERT_EQ(ticks.size(), 11u);
  ASSERT_EQ(acks.size(), 11u);
  for (std::uint64_t step = 0; step <= 10; ++step) {
    EXPECT_EQ(ticks[step].header().step(), step);
    EXPECT_EQ(ticks[step].final_tick(), step == 10) << step;
    EXPECT_EQ(acks[step].header().step(), step);
    EXPECT_EQ(acks[step].member().to_string(), "host");
    EXPECT_FALSE(acks[step].failed());
    EXPECT_EQ(acks[step].components_run(), 3u) << "feeder, consumer and producer at step " << step;
    // Delay 0: the consumer runs only after the producer's sample of the same step arrived.
    ASSERT_TRUE(seen->at(step).has_value()) << step;
    EXPECT_DOUBLE_EQ(*seen->at(step), 100.0 * static_cast<double>(step) + 1.0);
  }
}

// A co-located `robodds run` (HostOptions::lockstep_in_memory): the coordinator and the host
// half exchange ticks and acknowledgements through the host's own in-memory bus, so nothing of the
// protocol reaches the run's bus (DDS there), and the components see the same steps and samples.
/// Adds a "consumer" type that observes plant/state on the bus (observe_local) into *seen: robot
/// and step of each sample, in write order.
void add_observer(NodeHarness& h, std::shared_ptr<std::vector<std::pair<std::uint32_t, std::uint64_t>>> seen) {
  h.add_script("consumer",
               [seen](ComponentContext& ctx) {
                 ctx.observe_local<idl::RobotState>("plant/state", [seen](const idl::RobotState& s, const SampleMeta&) {
                   seen->emplace_back(s.robot_id(), s.header().step());
                 });
               },
               [](const StepInfo&) {});
}

TEST(HostLoop, ObserveLocalSeesEveryWriteInOrderAndNeedsEveryComponentInTheProcess) {
  NodeHarness h(kScenario);
  add_producer(h);
  auto seen = std::make_shared<std::vector<std::pair<std::uint32_t, std::uint64_t>>>();
  add_observer(h, seen);
  h.run({"producer", "consumer"});
  ASSERT_EQ(seen->size(), 22u) << "11 steps, 2 robots";
  for (std::size_t i = 0; i < seen->size(); ++i) {
    EXPECT_EQ((*seen)[i], std::make_pair(static_cast<std::uint32_t>(1 + i % 2), static_cast<std::uint64_t>(i / 2)));
  }

  NodeHarness across(kScenario);
  add_producer(across);
  add_observer(across, std::make_shared<std::vector<std::pair<std::uint32_t, std::uint64_t>>>());
  across.set_single_process(false);
  EXPECT_NE(across.run_error<ConfigError>({"producer", "consumer"}).find("observe_local(plant/state) needs every component in this process"),
            std::string::npos);
}

TEST(HostLoop, InMemoryLockstepKeepsTicksAndAcksOffTheBusWithTheSameResults) {
  NodeHarness h(kScenario);
  add_producer(h);
  auto seen = std::make_shared<Seen>();
  add_consumer(h, Subscription::instances({1, 2}), seen);
  const auto& ticks = h.record<idl::SimTick>("sim/clock");
  const auto& acks = h.record<idl::StepDone>("sim/step_done");
  h.options().lockstep_in_memory = true;
  const RunStats stats = h.run({"consumer", "producer"});

  EXPECT_EQ(stats.steps, 11u);
  EXPECT_TRUE(ticks.empty()) << ticks.size() << " ticks on the run's bus";
  EXPECT_TRUE(acks.empty()) << acks.size() << " acknowledgements on the run's bus";
  ASSERT_EQ(seen->size(), 11u);
  for (std::uint64_t step = 0; step <= 10; ++step) {
    ASSERT_TRUE(seen->at(step).has_value()) << step;
    EXPECT_DOUBLE_EQ(*seen->at(step), 100.0 * static_cast<double>(step) + 1.0) << step;
  }
}

TEST(HostLoop, InMemoryLockstepStillFailsTheRunWithTheComponentsName) {
  NodeHarness h(kScenario);
  add_producer(h);
  h.add_script("consumer", nullptr, [](const StepInfo& info) {
    if (info.step == 3) {
      throw std::runtime_error("boom");
    }
  });
  h.options().lockstep_in_memory = true;
  const std::string error = h.run_error<RunError>({"producer", "consumer"});
  EXPECT_NE(error.find("component 'consumer' failed at step 3: boom"), std::string::npos) << error;
}

TEST(HostLoop, AComponentWithAPeriodRunsOnlyOnDueSteps) {
  NodeHarness h(kScenario);
  add_producer(h);
  auto seen = std::make_shared<Seen>();
  add_consumer(h, Subscription::instances({1}), seen, 25.0);  // 100 Hz / 25 Hz = every 4 steps
  const auto& acks = h.record<idl::StepDone>("sim/step_done");
  h.run({"producer", "consumer"});

  std::vector<std::uint64_t> steps;
  for (const auto& [step, x] : *seen) {
    steps.push_back(step);
  }
  EXPECT_EQ(steps, (std::vector<std::uint64_t>{0, 4, 8}));
  ASSERT_EQ(acks.size(), 11u);
  EXPECT_EQ(acks[4].components_run(), 3u);
  EXPECT_EQ(acks[5].components_run(), 2u) << "the consumer is not due at step 5";
}

TEST(HostLoop, AnInputDelayedByOneReadsThePreviousStep) {
  NodeHarness h(kScenario);
  add_producer(h);
  auto seen = std::make_shared<Seen>();
  add_consumer(h, Subscription::instances({1, 2}).delayed(1), seen);
  h.run({"consumer", "producer"});

  ASSERT_EQ(seen->size(), 11u);
  EXPECT_FALSE(seen->at(0).has_value()) << "nothing is readable at step 0 with delay 1";
  for (std::uint64_t step = 1; step <= 10; ++step) {
    ASSERT_TRUE(seen->at(step).has_value()) << step;
    EXPECT_DOUBLE_EQ(*seen->at(step), 100.0 * static_cast<double>(step - 1) + 1.0) << step;
  }
}

TEST(HostLoop, AnInputWaitTimesOutNamingComponentTopicInstanceAndStep) {
  NodeHarness h(kScenario);
  add_producer(h);
  auto seen = std::make_shared<Seen>();
  add_consumer(h, Subscription::instances({1, 2}), seen);
  for (ComponentSpec& c : h.scenario().components) {
    if (c.name == "producer") {
      c.robots = {1};
    }
  }
  h.options().input_timeout_s = 0.2;
  try {
    h.run({"producer", "consumer"});
    FAIL() << "expected a RunError";
  } catch (const RunError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("component 'consumer'"), std::string::npos) << what;
    EXPECT_NE(what.find("plant/state"), std::string::npos) << what;
    EXPECT_NE(what.find("robot_id=2"), std::string::npos) << what;
    EXPECT_NE(what.find("at step 0"), std::string::npos) << what;
  }
  EXPECT_TRUE(seen->empty());
}

TEST(HostLoop, AnInstanceNoProducerDeclaresIsRefusedBeforeTheFirstTick) {
  // A pair-keyed topic's producers declare its instances (RunContext::produced_instances): a
  // consumer waiting for another one would wait until its input timeout; refused at configuration.
  const std::uint64_t pair12 = 1ULL << 32 | 2, pair23 = 2ULL << 32 | 3;
  NodeHarness h(kScenario);
  h.add_script("consumer",
               [=](ComponentContext& ctx) {
                 ctx.subscribe<idl::UwbRanges>("sensor/uwb", Subscription::instances({pair12, pair23}));
               },
               [](const StepInfo&) {});
  h.assign_producers({{"sensor/uwb", {{1, {"uwb"}}, {2, {"uwb"}}}}});
  h.produce_instances({{"sensor/uwb", {pair12, 2ULL << 32 | 1}}});
  h.options().input_timeout_s = 30.0;  // not reached: refused before the first tick
  const std::string error = h.run_error<ConfigError>({"consumer"});
  EXPECT_EQ(error.substr(error.find("components: ")),
            "components: lockstep: component 'consumer' waits at every step for sensor/uwb (robot_id=2 peer_id=3), an instance "
            "its producer 'uwb' does not publish (the scenario's producers declare robot_id=1 peer_id=2, robot_id=2 peer_id=1); "
            "give the producer that instance, or take it out of 'consumer'");
  h.produce_instances({{"sensor/uwb", {pair12, pair23}}});
  h.options().input_timeout_s = 0.2;  // declared: it waits (nobody publishes here) and times out
  EXPECT_NE(h.run_error<RunError>({"consumer"}).find("waited 0.2 s at step 0 for topic sensor/uwb"), std::string::npos);
}

/// Outputs of a two-stage pipeline (producer -> relay with delay 1 -> estimate/pose), and in
/// *max_outstanding the most ticks the coordinator had sent but not seen acknowledged.
std::vector<std::pair<std::uint64_t, double>> pipeline_outputs(std::size_t window, std::uint64_t* max_outstanding) {
  NodeHarness h(kScenario);
  auto ticks = std::make_shared<std::uint64_t>(0);
  auto acks = std::make_shared<std::uint64_t>(0);
  *max_outstanding = 0;
  const TopicInfo& clock = topic_info("sim/clock");
  const TopicInfo& done = topic_info("sim/step_done");
  auto tick_reader = h.bus().reader(clock.name, clock.type_name, "lockstep_local", [=](const void*, const SampleMeta&) {
    ++*ticks;
    *max_outstanding = std::max(*max_outstanding, *ticks - *acks);
  }, [](const std::string&) {});
  auto ack_reader = h.bus().reader(done.name, done.type_name, "lockstep_local", [=](const void*, const SampleMeta&) { ++*acks; },
                                   [](const std::string&) {});
  add_producer(h);
  auto input = std::make_shared<Input<idl::RobotState>*>(nullptr);
  auto out = std::make_shared<Output<idl::PoseEstimate>*>(nullptr);
  h.add_script("consumer",
               [input, out](ComponentContext& ctx) {
                 *input = &ctx.subscribe<idl::RobotState>("plant/state", Subscription::instances(ctx.robot_keys()).delayed(1));
                 *out = &ctx.advertise<idl::PoseEstimate>("estimate/pose");
               },
               [input, out](const StepInfo&) {
                 for (std::uint32_t id : {1u, 2u}) {
                   idl::PoseEstimate e;
                   e.robot_id(id);
                   for (const idl::RobotState& s : (*input)->take_new(id)) {
                     e.x(e.x() + s.x());
                   }
                   (*out)->publish(e);
                 }
               });
  const auto& estimates = h.record<idl::PoseEstimate>("estimate/pose");
  h.options().lockstep_window = window;
  h.run({"consumer", "producer"});
  std::vector<std::pair<std::uint64_t, double>> result;
  for (const idl::PoseEstimate& e : estimates) {
    result.emplace_back(e.header().step(), e.x());
  }
  return result;
}

TEST(HostLoop, ALockstepWindowAboveOneGivesTheSameOutputs) {
  std::uint64_t outstanding = 0;
  const auto strict = pipeline_outputs(1, &outstanding);
  EXPECT_EQ(outstanding, 1u) << "window 1: the next tick waits for the acknowledgement";
  ASSERT_EQ(strict.size(), 22u);
  EXPECT_DOUBLE_EQ(strict[2].second, 1.0) << "step 1 reads robot 1's state of step 0";
  EXPECT_EQ(pipeline_outputs(4, &outstanding), strict);
  EXPECT_EQ(outstanding, 4u) << "window 4: four ticks sent before the first acknowledgement";
  EXPECT_EQ(pipeline_outputs(16, &outstanding), strict);
  EXPECT_EQ(outstanding, 11u) << "every tick of the run at once";
}

TEST(HostLoop, AThrowingComponentFailsTheRunWithItsName) {
  NodeHarness h(kScenario);
  add_producer(h);
  h.add_script("consumer", nullptr, [](const StepInfo& info) {
    if (info.step == 3) {
      throw std::runtime_error("boom");
    }
  });
  const auto& acks = h.record<idl::StepDone>("sim/step_done");
  try {
    h.run({"producer", "consumer"});
    FAIL() << "expected a RunError";
  } catch (const RunError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("component 'consumer' failed at step 3: boom"), std::string::npos) << what;
  }
  ASSERT_FALSE(acks.empty());
  EXPECT_TRUE(acks.back().failed()) << "the host tells the coordinator why it stops";
}

// A host that runs until stopped (a component executable on a robot, real time): the stop
// signal is its normal end, components finish; without stop_ends_run it is an interruption.
TEST(HostLoop, RealTimeStopEndsTheRunOnlyWhenAskedTo) {
  for (const bool stop_ends_run : {true, false}) {
    NodeHarness h(R"(name: until_stopped
step_s: 0.01
duration_s: 1000.0
seed: 1
robots:
  - {id: 1}
components:
  - {name: ticker, type: ticker}
)");
    std::atomic<bool> stop{false};
    int steps = 0;
    bool finished = false;
    h.add_script("ticker", nullptr,
                 [&](const StepInfo&) {
                   if (++steps == 3) {
                     stop = true;  // as the signal handler would
                   }
                 },
                 [&](const StepInfo&) { finished = true; });
    h.set_mode(TimeMode::kRealtime);
    h.options().stop = &stop;
    h.options().stop_ends_run = stop_ends_run;
    if (stop_ends_run) {
      const RunStats stats = h.run({"ticker"});
      EXPECT_TRUE(finished);
      EXPECT_GE(steps, 3);
      EXPECT_LT(stats.steps, 1000u);  // ended long before duration_s
    } else {
      EXPECT_THROW(h.run({"ticker"}), RunError);
      EXPECT_FALSE(finished);
    }
  }
}

// `robodds run --realtime`: the first signal (graceful_stop) ends the run cleanly after the step
// it is at (components finish, stopped_by "signal"); the runner's stop_at_step ends it after
// that step exactly, also when it comes before the run starts.
TEST(HostLoop, RealTimeGracefulStopEndsTheRunCleanlyAtTheNextStep) {
  const char* scenario = R"(name: graceful
step_s: 0.01
duration_s: 3.0
seed: 1
robots:
  - {id: 1}
components:
  - {name: ticker, type: ticker}
)";
  {
    NodeHarness h(scenario);
    std::atomic<bool> graceful{false};
    std::atomic<bool> abort{false};
    std::uint64_t last_step = 0;
    std::uint64_t finished_at = 0;
    bool finished = false;
    h.add_script("ticker", nullptr,
                 [&](const StepInfo& info) {
                   last_step = info.step;
                   if (info.step >= 3) {
                     graceful = true;  // as the first signal would
                   }
                 },
                 [&](const StepInfo& info) {
                   finished = true;
                   finished_at = info.step;
                 });
    h.set_mode(TimeMode::kRealtime);
    h.options().stop = &abort;
    h.options().graceful_stop = &graceful;
    const RunStats stats = h.run({"ticker"});
    EXPECT_TRUE(finished);
    EXPECT_EQ(stats.stopped_by, "signal");
    EXPECT_EQ(finished_at, last_step) << "ends after the step it was at";
    EXPECT_EQ(stats.steps, last_step + 1);
    EXPECT_LT(stats.steps, 100u);  // ended long before duration_s (300 steps)
  }
  {
    NodeHarness h(scenario);
    std::atomic<std::uint64_t> stop_at{5};  // sent before the run's first step
    std::uint64_t finished_at = 0;
    h.add_script("ticker", nullptr, [](const StepInfo&) {}, [&](const StepInfo& info) { finished_at = info.step; });
    h.set_mode(TimeMode::kRealtime);
    h.options().stop_at_step = &stop_at;
    const RunStats stats = h.run({"ticker"});
    EXPECT_EQ(stats.stopped_by, "signal");
    EXPECT_EQ(finished_at, 5u);
    EXPECT_EQ(stats.steps, 6u);
  }
  {
    NodeHarness h(R"(name: short
step_s: 0.01
duration_s: 0.05
seed: 1
robots:
  - {id: 1}
components:
  - {name: ticker, type: ticker}
)");
    std::atomic<std::uint64_t> stop_at{kNoStopStep};
    h.add_script("ticker", nullptr, [](const StepInfo&) {}, nullptr);
    h.set_mode(TimeMode::kRealtime);
    h.options().stop_at_step = &stop_at;
    const RunStats stats = h.run({"ticker"});
    EXPECT_EQ(stats.stopped_by, "") << "no stop asked: the run goes to its end";
    EXPECT_EQ(stats.steps, 6u);
  }
}

/// Logs on_start() and on_step() calls, to check the order the host calls them in.
class StartLogger : public Component {
 public:
  explicit StartLogger(std::shared_ptr<std::vector<std::string>> log) : log_(std::move(log)) {}
  void configure(ComponentContext&) override {}
  void on_start() override { log_->push_back("start"); }
  void on_step(const StepInfo& info) override { log_->push_back("step " + std::to_string(info.step)); }

 private:
  std::shared_ptr<std::vector<std::string>> log_;
};

// on_start() runs once, before the first step, in both modes (real time: before the clock's first
// due step, so one-off work there does not make step 0 late).
TEST(HostLoop, OnStartRunsOnceBeforeTheFirstStepInBothModes) {
  for (const TimeMode mode : {TimeMode::kLockstep, TimeMode::kRealtime}) {
    NodeHarness h(R"(name: start_hook
step_s: 0.01
duration_s: 0.05
seed: 1
robots:
  - {id: 1}
components:
  - {name: logger, type: logger}
)");
    auto log = std::make_shared<std::vector<std::string>>();
    h.registry().add({"logger", "logs its calls", testing::kNoParamsFile, [log] { return std::make_unique<StartLogger>(log); },
                      testing::no_params, nullptr});
    h.set_mode(mode);
    h.run({"logger"});
    ASSERT_GE(log->size(), 2u);
    EXPECT_EQ(log->front(), "start");
    EXPECT_EQ(std::count(log->begin(), log->end(), "start"), 1);
    EXPECT_EQ((*log)[1].rfind("step ", 0), 0u);
  }
}

}  // namespace
}  // namespace robodds
