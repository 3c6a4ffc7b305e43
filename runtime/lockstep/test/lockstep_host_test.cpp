#include "runtime/lockstep/lockstep_host.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <thread>

#include "runtime/bus/memory_bus.hpp"
#include "runtime/topics/topic_catalog.hpp"

namespace robodds {
namespace {

/// The profile the host and the coordinator use for a lockstep topic (not co-located).
std::string profile_of(const std::string& topic) { return qos_profile_for(topic_info(topic), TimeMode::kLockstep, false); }

class Recorder : public Component {
 public:
  explicit Recorder(std::vector<std::uint64_t>* steps, bool* finished) : steps_(steps), finished_(finished) {}
  void configure(ComponentContext&) override {}
  void on_step(const StepInfo& info) override { steps_->push_back(info.step); }
  void on_finish(const StepInfo&) override { *finished_ = true; }

 private:
  std::vector<std::uint64_t>* steps_;
  bool* finished_;
};

/// A bus in front of another that logs "write <topic>" and "wait <topic>" for every call on the
/// writers it hands out (the order in which a host writes and waits for acknowledgements).
class CallLogBus : public Bus {
 public:
  explicit CallLogBus(Bus& inner) : inner_(inner) {}
  std::shared_ptr<WriterHandle> writer(const std::string& topic, const std::string& type_name,
                                       const std::string& profile) override {
    return std::make_shared<Handle>(inner_.writer(topic, type_name, profile), &calls);
  }
  std::shared_ptr<ReaderHandle> reader(const std::string& topic, const std::string& type_name, const std::string& profile,
                                       SampleCallback on_sample, ReaderEventCallback on_event) override {
    return inner_.reader(topic, type_name, profile, std::move(on_sample), std::move(on_event));
  }
  void flush(std::chrono::milliseconds timeout) override { inner_.flush(timeout); }
  std::vector<std::string> calls;

 private:
  struct Handle : WriterHandle {
    Handle(std::shared_ptr<WriterHandle> inner, std::vector<std::string>* calls) : inner(std::move(inner)), calls(calls) {}
    void write(const void* sample) override {
      calls->push_back("write " + topic());
      inner->write(sample);
    }
    const std::string& topic() const override { return inner->topic(); }
    bool wait_acknowledged(std::chrono::milliseconds timeout) override {
      calls->push_back("wait " + topic());
      return inner->wait_acknowledged(timeout);
    }
    std::shared_ptr<WriterHandle> inner;
    std::vector<std::string>* calls;
  };
  Bus& inner_;
};

/// One component ("recorder", every `period` steps) behind a LockstepHost on the in-memory bus,
/// a tick publisher standing in for the coordinator, and a recorder of the acknowledgements.
struct HostFixture : ::testing::Test {
  MemoryBus bus;
  Notifier notifier;
  Scenario scenario;
  ComponentSpec spec;
  RunContext run;
  HostOptions options;
  LockstepHost::Slots slots;
  std::vector<std::uint64_t> steps_run;
  bool finished = false;
  std::vector<idl::StepDone> acks;
  std::shared_ptr<ReaderHandle> ack_reader;
  StepState tick_state;
  std::unique_ptr<Output<idl::SimTick>> tick_output;

  void SetUp() override {
    scenario.step_s = 0.01;
    scenario.duration_s = 0.05;  // steps 0..5
    spec.name = "recorder";
    spec.type = "recorder";
    run.scenario = &scenario;
    run.bus = &bus;
    run.notifier = &notifier;
    options.member = "m";
    options.components = {"recorder"};
    options.run_id = 9;
    ack_reader = bus.reader("sim/step_done", topic_info("sim/step_done").type_name, profile_of("sim/step_done"),
                            [this](const void* s, const SampleMeta&) { acks.push_back(*static_cast<const idl::StepDone*>(s)); }, nullptr);
    tick_output = std::make_unique<Output<idl::SimTick>>(bus.writer("sim/clock", topic_info("sim/clock").type_name, profile_of("sim/clock")), &tick_state);
  }

  host_detail::ComponentSlot& add_slot(std::uint64_t period_steps) {
    auto slot = std::make_unique<host_detail::ComponentSlot>();
    slot->spec = &spec;
    slot->state.period_steps = period_steps;
    slot->component = std::make_unique<Recorder>(&steps_run, &finished);
    slot->context = std::make_unique<ComponentContext>(run, spec, ParamReader("recorder", {}), &slot->state);
    slots.push_back(std::move(slot));
    return *slots.back();
  }

  void tick(std::uint64_t step, std::uint64_t run_id = 9, double step_s = 0.0) {
    idl::SimTick t;
    t.run_id(run_id);
    t.step_s(step_s > 0.0 ? step_s : scenario.step_s);
    t.final_tick(step == scenario.last_step());
    tick_state.step = step;
    tick_output->publish(t);
  }
};

TEST_F(HostFixture, RunsDueComponentsAndAcknowledgesEveryTick) {
  add_slot(2);
  LockstepHost host(run, options, slots, *run.bus);
  host.begin(std::chrono::steady_clock::now());
  for (std::uint64_t step = 0; step <= 5; ++step) {
    EXPECT_FALSE(host.done());
    tick(step);
    EXPECT_TRUE(host.step());
    ASSERT_EQ(acks.size(), step + 1) << "tick " << step << " not acknowledged";
    EXPECT_EQ(acks.back().header().step(), step);
    EXPECT_EQ(acks.back().member().to_string(), "m");
    EXPECT_EQ(acks.back().run_id(), 9u);
    EXPECT_EQ(acks.back().components_run(), step % 2 == 0 ? 1u : 0u);
    EXPECT_FALSE(acks.back().failed());
  }
  EXPECT_EQ(steps_run, (std::vector<std::uint64_t>{0, 2, 4}));
  EXPECT_TRUE(finished);
  EXPECT_TRUE(host.done());
  EXPECT_EQ(host.steps_done(), 6u);
  EXPECT_EQ(run.figures.ticks, 6u);
  EXPECT_GE(run.figures.wall_time_s, 0.0);
}

TEST_F(HostFixture, AHostOfTheRunsScenarioAcknowledgesOnlyItsBusyStepsEachAnnouncingTheNext) {
  options.digest = {DigestEntry{"scenario", "/s.yaml", "1a2b"}};  // it loaded the coordinator's scenario
  add_slot(2);
  LockstepHost host(run, options, slots, *run.bus);
  host.begin(std::chrono::steady_clock::now());
  for (std::uint64_t step = 0; step <= 5; ++step) {
    tick(step);
    EXPECT_TRUE(host.step());
  }
  // Due at 0, 2, 4; step 5 is the last: the steps between are done when announced.
  std::vector<std::uint64_t> acked;
  std::vector<std::uint64_t> announced;
  for (const idl::StepDone& a : acks) {
    acked.push_back(a.header().step());
    announced.push_back(a.header().next_step());
  }
  EXPECT_EQ(acked, (std::vector<std::uint64_t>{0, 2, 4, 5}));
  EXPECT_EQ(announced, (std::vector<std::uint64_t>{2, 4, 5, 6}));
  EXPECT_EQ(steps_run, (std::vector<std::uint64_t>{0, 2, 4}));
  EXPECT_TRUE(finished);
  EXPECT_TRUE(host.done());
  EXPECT_EQ(host.steps_done(), 6u);
}

TEST_F(HostFixture, AHostWithoutTheRunsScenarioAcknowledgesEveryStep) {
  add_slot(3);  // no digest: a component executable, whose last step may not be the coordinator's
  LockstepHost host(run, options, slots, *run.bus);
  host.begin(std::chrono::steady_clock::now());
  for (std::uint64_t step = 0; step <= 5; ++step) {
    tick(step);
    EXPECT_TRUE(host.step());
    ASSERT_EQ(acks.size(), step + 1);
    EXPECT_EQ(acks.back().header().next_step(), step + 1);
  }
}

TEST_F(HostFixture, TicksOfOtherRunsAreIgnored) {
  add_slot(1);
  LockstepHost host(run, options, slots, *run.bus);
  host.begin(std::chrono::steady_clock::now());
  tick(0, 8);
  EXPECT_FALSE(host.step());
  EXPECT_TRUE(acks.empty());
  EXPECT_TRUE(steps_run.empty());
}

TEST_F(HostFixture, ATickWithAnotherStepIsAnError) {
  add_slot(1);
  LockstepHost host(run, options, slots, *run.bus);
  host.begin(std::chrono::steady_clock::now());
  tick(0, 9, 0.02);
  try {
    host.step();
    FAIL() << "expected a RunError";
  } catch (const RunError& e) {
    EXPECT_STREQ(e.what(), "m: the coordinator's step is 0.02 s, this host's 0.01 s (--step or the scenario's step_s must agree)");
  }
  EXPECT_TRUE(steps_run.empty());
}

TEST_F(HostFixture, NoTickTimesOut) {
  add_slot(1);
  options.start_timeout_s = 0.05;
  LockstepHost host(run, options, slots, *run.bus);
  host.begin(std::chrono::steady_clock::now());
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  try {
    host.step();
    FAIL() << "expected a RunError";
  } catch (const RunError& e) {
    EXPECT_STREQ(e.what(), "m: no tick on sim/clock for 0.1 s after start: is the coordinator (robodds run) alive and on the same domain?");
  }
}

// The launcher knows how the host was started (a component executable: which coordinator, and
// that real time needs none) and gives the advice the error ends with.
TEST_F(HostFixture, NoTickTimeoutEndsWithTheLaunchersAdvice) {
  add_slot(1);
  options.start_timeout_s = 0.05;
  options.no_tick_advice = "is `robodds coordinate --members m` running? Or give --realtime";
  LockstepHost host(run, options, slots, *run.bus);
  host.begin(std::chrono::steady_clock::now());
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  try {
    host.step();
    FAIL() << "expected a RunError";
  } catch (const RunError& e) {
    EXPECT_STREQ(e.what(), "m: no tick on sim/clock for 0.1 s after start: is `robodds coordinate --members m` running? Or give --realtime");
  }
}

TEST_F(HostFixture, MissingInputTimesOutNamingComponentStepAndTopic) {
  host_detail::ComponentSlot& slot = add_slot(1);
  slot.context->subscribe<idl::RobotState>("plant/state", Subscription::instances({1}));
  options.input_timeout_s = 0.05;
  LockstepHost host(run, options, slots, *run.bus);
  host.begin(std::chrono::steady_clock::now());
  tick(0);
  EXPECT_TRUE(host.step());  // took the tick; the component waits
  EXPECT_TRUE(acks.empty());
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  try {
    host.step();
    FAIL() << "expected a RunError";
  } catch (const RunError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("lockstep: component 'recorder' waited 0.1 s at step 0 for topic plant/state, ", 0), 0u)
        << e.what();
  }
}

/// A bus in front of another that claims the writer history of a DDS bus whose `lockstep`
/// writers keep `depth` samples (history_checkpoints.hpp).
class ShallowHistoryBus : public Bus {
 public:
  ShallowHistoryBus(Bus& inner, std::size_t depth) : inner_(inner), depth_(depth) {}
  std::shared_ptr<WriterHandle> writer(const std::string& topic, const std::string& type_name,
                                       const std::string& profile) override {
    return inner_.writer(topic, type_name, profile);
  }
  std::shared_ptr<ReaderHandle> reader(const std::string& topic, const std::string& type_name, const std::string& profile,
                                       SampleCallback on_sample, ReaderEventCallback on_event) override {
    return inner_.reader(topic, type_name, profile, std::move(on_sample), std::move(on_event));
  }
  void flush(std::chrono::milliseconds timeout) override { inner_.flush(timeout); }
  std::optional<std::size_t> writer_history_depth(const std::string& profile) const override {
    return profile == "lockstep" ? std::optional<std::size_t>(depth_) : std::nullopt;
  }

 private:
  Bus& inner_;
  std::size_t depth_;
};

/// A component due every 10 steps reading plant/state of robot 1, behind a host whose producers'
/// writers keep `depth` samples (0: no writer history, as in memory): the steps the host
/// acknowledged when plant/state arrived up to step 2 only, after ticks 0-3.
std::vector<std::uint64_t> acked_without_step_3(HostFixture& f, std::size_t depth) {
  ShallowHistoryBus shallow(f.bus, depth);
  if (depth > 0) {
    f.run.bus = &shallow;
  }
  host_detail::ComponentSlot& slot = f.add_slot(10);
  slot.context->subscribe<idl::RobotState>("plant/state", Subscription::instances({1}));
  LockstepHost host(f.run, f.options, f.slots, f.bus);
  host.begin(std::chrono::steady_clock::now());
  StepState producer;
  Output<idl::RobotState> states(f.bus.writer("plant/state", topic_info("plant/state").type_name, profile_of("plant/state")),
                                 &producer);
  for (std::uint64_t step = 0; step <= 3; ++step) {
    if (step <= 2) {
      producer.step = step;
      idl::RobotState s;
      s.robot_id(1);
      states.publish(s);
    }
    f.tick(step);
    host.step();
    host.step();
  }
  std::vector<std::uint64_t> acked;
  for (const idl::StepDone& a : f.acks) {
    acked.push_back(a.header().step());
  }
  f.run.bus = &f.bus;
  return acked;
}

TEST_F(HostFixture, WithAShortWriterHistoryASlowComponentsHostWaitsForItsInputsBetweenDueSteps) {
  // depth 3, window 1, delay 0: waits every 3 steps (1 + 3 + 0 - 1 = 3), so step 3 waits for
  // plant/state of step 3; without a writer history only the due steps (every 10) wait.
  EXPECT_EQ(acked_without_step_3(*this, 3), (std::vector<std::uint64_t>{0, 1, 2}));
}

TEST_F(HostFixture, WithoutAWriterHistoryOnlyTheDueStepsWait) {
  EXPECT_EQ(acked_without_step_3(*this, 0), (std::vector<std::uint64_t>{0, 1, 2, 3}));
}

TEST_F(HostFixture, AHistoryCheckpointIsABusyStepToo) {
  // As above (checkpoints every 3 steps), acknowledging only busy steps: step 0 announces the
  // checkpoint at 3, where plant/state of step 3 never comes, so nothing after 0 is acknowledged.
  options.digest = {DigestEntry{"scenario", "/s.yaml", "1a2b"}};
  EXPECT_EQ(acked_without_step_3(*this, 3), (std::vector<std::uint64_t>{0}));
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].header().next_step(), 3u);
}

TEST_F(HostFixture, FailureIsAcknowledgedWithItsReason) {
  add_slot(1);
  LockstepHost host(run, options, slots, *run.bus);
  host.begin(std::chrono::steady_clock::now());
  tick(0);
  host.step();
  tick(1);
  host.step();
  host.publish_failure("boom");
  ASSERT_EQ(acks.size(), 3u);
  EXPECT_TRUE(acks.back().failed());
  EXPECT_EQ(acks.back().error().to_string(), "boom");
  EXPECT_EQ(acks.back().header().step(), 1u);
}

// The host exits right after its failure report; across processes the report is lost when the
// participant's goodbye overtakes it (integration.qos_mismatch under load, issue 9 finding 10).
// So the report must be acknowledged before publish_failure() returns.
TEST_F(HostFixture, FailureReportIsAcknowledgedBeforeReturning) {
  add_slot(1);
  CallLogBus logged(bus);
  run.bus = &logged;
  LockstepHost host(run, options, slots, *run.bus);
  host.begin(std::chrono::steady_clock::now());
  tick(0);
  host.step();
  host.publish_failure("boom");
  ASSERT_EQ(acks.size(), 2u);
  EXPECT_TRUE(acks.back().failed());
  EXPECT_EQ(logged.calls, (std::vector<std::string>{"write sim/step_done", "write sim/step_done", "wait sim/step_done"}));
}

}  // namespace
}  // namespace robodds
