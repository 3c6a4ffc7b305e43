#include "runtime/lockstep/lockstep_coordinator.hpp"

#include <gtest/gtest.h>

#include <string>
#include <thread>

#include "runtime/bus/memory_bus.hpp"
#include "runtime/topics/topic_catalog.hpp"

namespace robodds {
namespace {

/// The profile the host and the coordinator use for a lockstep topic (not co-located).
std::string profile_of(const std::string& topic) { return qos_profile_for(topic_info(topic), TimeMode::kLockstep, false); }

/// The message of the RunError the coordinator's next poll() throws ("" if none).
std::string poll_error(LockstepCoordinator& coordinator) {
  try {
    coordinator.poll();
  } catch (const RunError& e) {
    return e.what();
  }
  return "";
}

/// A coordinator for members {"a", "b"} on the in-memory bus, with a recorder of its ticks and a
/// way to acknowledge as a member.
struct CoordinatorFixture : ::testing::Test {
  MemoryBus bus;
  Notifier notifier;
  Scenario scenario;
  RunContext run;
  HostOptions options;
  std::vector<std::uint64_t> ticks;
  std::vector<bool> final_flags;
  std::shared_ptr<ReaderHandle> tick_reader;
  StepState ack_state;
  std::unique_ptr<Output<idl::StepDone>> ack_output;

  void SetUp() override {
    scenario.step_s = 0.01;
    scenario.duration_s = 0.05;  // steps 0..5
    run.scenario = &scenario;
    run.bus = &bus;
    run.notifier = &notifier;
    options.members = {"a", "b"};
    options.run_id = 9;
    tick_reader = bus.reader("sim/clock", topic_info("sim/clock").type_name, profile_of("sim/clock"), [this](const void* s, const SampleMeta&) {
      const auto& tick = *static_cast<const idl::SimTick*>(s);
      ticks.push_back(tick.header().step());
      final_flags.push_back(tick.final_tick());
    }, nullptr);
    ack_output = std::make_unique<Output<idl::StepDone>>(bus.writer("sim/step_done", topic_info("sim/step_done").type_name, profile_of("sim/step_done")), &ack_state);
  }

  /// `next_ack`: the step of the member's next acknowledgement (0: step + 1).
  void ack(const std::string& member, std::uint64_t step, const std::string& error = "", std::uint64_t run_id = 9,
           std::uint64_t next_ack = 0) {
    idl::StepDone done;
    done.member(member);
    done.run_id(run_id);
    done.failed(!error.empty());
    done.error(error);
    ack_state.step = step;
    ack_output->publish_next_at(done, next_ack > 0 ? next_ack : step + 1);
  }
};

TEST_F(CoordinatorFixture, WindowBoundsTheOutstandingTicks) {
  options.lockstep_window = 2;
  LockstepCoordinator coordinator(run, options, *run.bus);
  coordinator.begin(std::chrono::steady_clock::now());
  EXPECT_TRUE(coordinator.poll());
  EXPECT_EQ(ticks, (std::vector<std::uint64_t>{0, 1}));
  EXPECT_FALSE(coordinator.poll());  // nothing acknowledged: nothing moves
  ack("a", 0);
  EXPECT_FALSE(coordinator.poll());  // step 0 still waits for b
  EXPECT_EQ(coordinator.acknowledged_steps(), 0u);
  ack("b", 0);
  EXPECT_TRUE(coordinator.poll());
  EXPECT_EQ(coordinator.acknowledged_steps(), 1u);
  EXPECT_EQ(ticks, (std::vector<std::uint64_t>{0, 1, 2}));
}

TEST_F(CoordinatorFixture, StrictWindowRunsToTheFinalTick) {
  std::vector<std::uint64_t> progress;
  options.progress = [&progress](std::uint64_t step, std::uint64_t) { progress.push_back(step); };
  LockstepCoordinator coordinator(run, options, *run.bus);
  coordinator.begin(std::chrono::steady_clock::now());
  for (std::uint64_t step = 0; step <= 5; ++step) {
    EXPECT_FALSE(coordinator.done());
    coordinator.poll();
    EXPECT_EQ(ticks.size(), step + 1) << "window 1: one tick per acknowledged step";
    ack("a", step);
    ack("b", step);
  }
  coordinator.poll();
  EXPECT_TRUE(coordinator.done());
  EXPECT_EQ(coordinator.acknowledged_steps(), 6u);
  EXPECT_EQ(final_flags, (std::vector<bool>{false, false, false, false, false, true}));
  EXPECT_EQ(progress, (std::vector<std::uint64_t>{0, 1, 2, 3, 4, 5}));
}

TEST_F(CoordinatorFixture, AnAcknowledgementThatAnnouncesALaterOneCoversTheStepsBetween) {
  options.tick_timeout_s = 0.1;
  LockstepCoordinator coordinator(run, options, *run.bus);
  coordinator.begin(std::chrono::steady_clock::now());
  coordinator.poll();
  ack("a", 0, "", 9, 3);  // a has no work before step 3
  for (std::uint64_t step = 0; step <= 2; ++step) {
    ack("b", step);
    coordinator.poll();
  }
  EXPECT_EQ(coordinator.acknowledged_steps(), 3u);
  EXPECT_EQ(ticks, (std::vector<std::uint64_t>{0, 1, 2, 3}));
  ack("b", 3);
  EXPECT_FALSE(coordinator.poll());  // step 3 waits for a's announced acknowledgement
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  EXPECT_EQ(poll_error(coordinator), "lockstep: no acknowledgement of step 3 within 0.1 s from group 'a' (newest sample: step 0) on sim/step_done");
}

TEST_F(CoordinatorFixture, AGroupWhoseAcknowledgementCoversTheStepIsNotNamedAsMissing) {
  options.members = {"a", "b", "c"};
  options.tick_timeout_s = 0.1;
  LockstepCoordinator coordinator(run, options, *run.bus);
  coordinator.begin(std::chrono::steady_clock::now());
  coordinator.poll();
  ack("a", 0, "", 9, 5);  // done up to step 4
  ack("b", 0);
  ack("c", 0);
  coordinator.poll();
  EXPECT_EQ(coordinator.acknowledged_steps(), 1u);
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  EXPECT_EQ(poll_error(coordinator), "lockstep: no acknowledgement of step 1 within 0.1 s from groups 'b' (newest sample: step 0), "
                                     "'c' (newest sample: step 0) on sim/step_done");
}

TEST_F(CoordinatorFixture, FailedGroupIsReported) {
  LockstepCoordinator coordinator(run, options, *run.bus);
  coordinator.begin(std::chrono::steady_clock::now());
  coordinator.poll();
  ack("b", 0, "component 'pf' failed at step 0: boom");
  EXPECT_EQ(poll_error(coordinator), "group 'b' failed at step 0: component 'pf' failed at step 0: boom");
}

TEST_F(CoordinatorFixture, AcknowledgementsOfOtherRunsDoNotCount) {
  LockstepCoordinator coordinator(run, options, *run.bus);
  coordinator.begin(std::chrono::steady_clock::now());
  coordinator.poll();
  ack("a", 0, "", 8);
  ack("b", 0, "stale failure", 8);
  EXPECT_NO_THROW(coordinator.poll());
  EXPECT_EQ(coordinator.acknowledged_steps(), 0u);
}

TEST_F(CoordinatorFixture, MissingAcknowledgementTimesOutNamingTheGroup) {
  options.start_timeout_s = 0.05;
  LockstepCoordinator coordinator(run, options, *run.bus);
  coordinator.begin(std::chrono::steady_clock::now());
  coordinator.poll();
  ack("a", 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(poll_error(coordinator), "lockstep: no acknowledgement of step 0 within 0.1 s from group 'b' (nothing received yet) on sim/step_done");
}

// At the start several members may be missing (component executables not started): each is
// named, in the order of --members, not only the first by key.
TEST_F(CoordinatorFixture, MissingAcknowledgementsNameEveryMissingGroup) {
  options.members = {"c", "a", "b"};
  options.start_timeout_s = 0.05;
  LockstepCoordinator coordinator(run, options, *run.bus);
  coordinator.begin(std::chrono::steady_clock::now());
  coordinator.poll();
  ack("b", 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(poll_error(coordinator), "lockstep: no acknowledgement of step 0 within 0.1 s from groups 'c' (nothing received yet), "
                                     "'a' (nothing received yet) on sim/step_done");
}

}  // namespace
}  // namespace robodds
