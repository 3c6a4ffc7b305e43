// The lockstep input rule, without DDS: samples are handed to Input::on_sample directly.
#include "runtime/io/io.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "runtime/io/sample_checks.hpp"
#include "runtime/bus/memory_bus.hpp"

namespace robodds {
namespace {

idl::RobotState state(std::uint32_t robot, std::uint64_t step, std::uint64_t next_step, double x) {
  idl::RobotState s;
  s.robot_id(robot);
  s.header().step(step);
  s.header().next_step(next_step);
  s.x(x);
  return s;
}

/// Options of an input that expects robot 1, read `delay` steps late.
detail::InputOptions robot_one(std::uint64_t delay) {
  detail::InputOptions options;
  options.expected = {1};
  options.delay_steps = delay;
  options.key_names = "robot_id";
  return options;
}

class InputTest : public ::testing::Test {
 protected:
  StepState clock;
  Notifier notifier;
};

TEST_F(InputTest, WaitsUntilNextStepPassesTheConsumerStep) {
  detail::InputOptions options;
  options.expected = {1, 2};
  options.key_names = "robot_id";
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, options);
  std::string missing;
  EXPECT_FALSE(input.ready(0, &missing));
  EXPECT_NE(missing.find("robot_id"), std::string::npos) << missing;
  input.on_sample(state(1, 0, 10, 1.0));
  EXPECT_FALSE(input.ready(0, &missing));  // robot 2 still missing
  input.on_sample(state(2, 0, 10, 2.0));
  EXPECT_TRUE(input.ready(0, nullptr));
  EXPECT_TRUE(input.ready(9, nullptr));
  EXPECT_FALSE(input.ready(10, nullptr));
}

idl::RangeMeasurement range(std::uint32_t robot, std::uint32_t target, std::uint64_t step, std::uint64_t next_step, double r) {
  idl::RangeMeasurement m;
  m.robot_id(robot);
  m.target_id(target);
  m.header().step(step);
  m.header().next_step(next_step);
  m.range(r);
  return m;
}

// A robot switches from target 1 to target 2 at step 4: the consumer waits per robot, so it
// waits at step 4 for the (1, 2) sample it could not name in advance.
TEST_F(InputTest, RobotStreamsWaitPerRobotWhateverTheSecondKey) {
  detail::InputOptions options;
  options.expected = {1};
  options.by_robot = true;
  options.key_names = "robot_id, target_id";
  Input<idl::RangeMeasurement> input("sensor/range", "test", &clock, &notifier, options);
  std::string missing;
  EXPECT_FALSE(input.ready(0, &missing));
  EXPECT_EQ(missing, "robot_id=1 (any target_id) (nothing received yet)");
  input.on_sample(range(1, 1, 0, 2, 100.0));
  input.on_sample(range(1, 1, 2, 4, 101.0));
  input.on_sample(range(2, 1, 0, 2, 5.0));  // another robot: not wanted
  EXPECT_TRUE(input.ready(3, nullptr));
  EXPECT_FALSE(input.ready(4, &missing));  // the switch: the robot's next sample is due at 4
  EXPECT_NE(missing.find("target_id=1"), std::string::npos) << missing;
  input.on_sample(range(1, 2, 4, kNeverAgain, 300.0));  // the new target, then the robot leaves
  EXPECT_TRUE(input.ready(4, nullptr));
  EXPECT_TRUE(input.ready(1000, nullptr));
  clock.step = 2;
  const auto first = input.take_new_of_robot(1);  // step 4 is not readable yet
  ASSERT_EQ(first.size(), 2u);
  EXPECT_DOUBLE_EQ(first[0].range(), 100.0);
  EXPECT_DOUBLE_EQ(first[1].range(), 101.0);
  clock.step = 4;
  ASSERT_NE(input.latest_of_robot(1), nullptr);
  EXPECT_EQ(input.latest_of_robot(1)->target_id(), 2u);  // the newest over both targets
  EXPECT_TRUE(input.take_new_of_robot(2).empty());
}

// Across processes each sample used to wake the executor, which found the input still not ready
// and slept again: a context switch per robot and topic. Now only the last missing stream wakes it.
TEST_F(InputTest, LockstepInputWakesOnceWhenTheLastStreamArrives) {
  detail::InputOptions options;
  options.expected = {1, 2, 3};
  options.key_names = "robot_id";
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, options);
  const std::uint64_t before = notifier.generation();
  input.on_sample(state(1, 0, 1, 1.0));  // nobody waits yet: no wake-up
  EXPECT_EQ(notifier.generation(), before);
  EXPECT_FALSE(input.ready(0, nullptr));  // the executor will wait for robots 2 and 3
  input.on_sample(state(2, 0, 1, 2.0));
  EXPECT_EQ(notifier.generation(), before);
  input.on_sample(state(3, 0, 1, 3.0));  // the last one: one wake-up
  EXPECT_EQ(notifier.generation(), before + 1);
  EXPECT_TRUE(input.ready(0, nullptr));
  input.on_sample(state(1, 1, 2, 1.0));  // ready was true: nobody waits
  EXPECT_EQ(notifier.generation(), before + 1);

  // Protocol inputs (ticks, acknowledgements) and real-time inputs wake at every sample.
  detail::InputOptions protocol = options;
  protocol.ignore_step = true;
  Input<idl::RobotState> ticks("sim/clock", "test", &clock, &notifier, protocol);
  ticks.on_sample(state(1, 0, 1, 1.0));
  ticks.on_sample(state(2, 0, 1, 1.0));
  EXPECT_EQ(notifier.generation(), before + 3);
  StepState realtime_clock;
  realtime_clock.mode = TimeMode::kRealtime;
  Input<idl::RobotState> live("plant/state", "test", &realtime_clock, &notifier, options);
  live.on_sample(state(1, 0, 1, 1.0));
  EXPECT_EQ(notifier.generation(), before + 4);
}

// A stream's samples announce the step of the next; one beyond it means a sample was lost (and
// could not be resent): the run ends naming the stream, instead of reading a gap as "no news".
TEST_F(InputTest, LockstepLostSampleEndsTheRun) {
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, robot_one(0));
  input.on_sample(state(1, 0, 5, 1.0));
  input.on_sample(state(1, 3, 8, 1.0));  // earlier than announced: allowed (an event moved it)
  input.on_sample(state(1, 8, 9, 1.0));  // exactly as announced
  EXPECT_TRUE(input.ready(8, nullptr));
  EXPECT_TRUE(input.lockstep_error().empty());
  input.on_sample(state(1, 10, 11, 1.0));  // step 9 never came
  try {
    input.ready(10, nullptr);
    FAIL() << "expected a RunError";
  } catch (const RunError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("plant/state (robot_id=1) lost samples"), std::string::npos) << what;
    EXPECT_NE(what.find("at step 9, came step 10"), std::string::npos) << what;
  }
  // Real time has no chain: a stream may skip steps there.
  StepState realtime_clock;
  realtime_clock.mode = TimeMode::kRealtime;
  Input<idl::RobotState> live("plant/state", "test", &realtime_clock, &notifier, robot_one(0));
  live.on_sample(state(1, 0, 1, 1.0));
  live.on_sample(state(1, 10, 11, 1.0));
  EXPECT_TRUE(live.lockstep_error().empty());
}

// A newest-only input reads at its due steps only: its writers may leave out the samples of the
// steps between (across processes they do). Skipping those is no loss; skipping a read step is.
TEST_F(InputTest, ANewestOnlyInputLosesASampleOnlyWhenItSkipsAReadStep) {
  detail::InputOptions options = robot_one(1);
  options.newest_only = true;
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, options);
  ASSERT_TRUE(input.newest_only());
  input.read_only(StepNeeds::of_component(10, 0, 1));  // due at 10, 20, ...: reads steps 9, 19, ...
  input.on_sample(state(1, 9, 10, 9.0));
  EXPECT_TRUE(input.ready(10, nullptr));
  input.on_sample(state(1, 19, 20, 19.0));  // steps 10..18 left out: none of them is read
  EXPECT_TRUE(input.ready(20, nullptr));
  EXPECT_TRUE(input.lockstep_error().empty());
  clock.step = 20;
  ASSERT_NE(input.latest(1), nullptr);
  EXPECT_EQ(input.latest(1)->x(), 19.0);
  input.on_sample(state(1, 30, 31, 30.0));  // step 29, read at 30, never came
  try {
    input.ready(30, nullptr);
    FAIL() << "expected a RunError";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("at step 20, came step 30"), std::string::npos) << e.what();
  }
}

TEST_F(InputTest, ANewestOnlyInputRefusesTakeNew) {
  detail::InputOptions options = robot_one(0);
  options.newest_only = true;
  Input<idl::RobotState> input("plant/state", "sensor", &clock, &notifier, options);
  input.on_sample(state(1, 0, 1, 1.0));
  clock.step = 0;
  EXPECT_THROW(input.take_new(1), ConfigError);
  std::vector<idl::RobotState> out;
  EXPECT_THROW(input.take_new(std::vector<std::uint64_t>{1}, out), ConfigError);
  EXPECT_THROW(input.take_new_of_robot(1), ConfigError);
  EXPECT_NE(input.latest(1), nullptr);
}

TEST_F(InputTest, ReadsOnlySamplesUpToTheCurrentStepMinusDelay) {
  detail::InputOptions options;
  options.expected = {1};
  options.delay_steps = 1;
  Input<idl::RobotState> input("plant/cmd", "test", &clock, &notifier, options);
  clock.step = 0;
  EXPECT_TRUE(input.ready(0, nullptr));  // nothing can be due before step 0
  input.on_sample(state(1, 0, 1, 10.0));
  input.on_sample(state(1, 1, 2, 11.0));  // already published for step 1
  EXPECT_EQ(input.latest(1), nullptr);    // at step 0 the delayed input has nothing
  clock.step = 1;
  ASSERT_NE(input.latest(1), nullptr);
  EXPECT_DOUBLE_EQ(input.latest(1)->x(), 10.0);
  clock.step = 2;
  EXPECT_DOUBLE_EQ(input.latest(1)->x(), 11.0);
}

TEST_F(InputTest, TakeNewReturnsEverySampleInOrderOnce) {
  Input<idl::RobotState> input("sensor/odometry", "test", &clock, &notifier, robot_one(0));
  input.on_sample(state(1, 0, 2, 0.0));
  input.on_sample(state(1, 2, 4, 2.0));
  clock.step = 3;
  auto first = input.take_new(1);
  ASSERT_EQ(first.size(), 2u);
  EXPECT_DOUBLE_EQ(first[1].x(), 2.0);
  EXPECT_TRUE(input.take_new(1).empty());
}

// Samples not yet readable stay queued, in order, however many are taken before them (the
// queue reuses its storage and drops what was taken: runtime/io/io.hpp, Slot).
TEST_F(InputTest, TakeNewKeepsTheOrderAcrossManyPartialTakes) {
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, robot_one(0));
  std::uint64_t next_step = 0;
  std::uint64_t next_x = 0;
  for (std::uint64_t round = 0; round < 4; ++round) {
    for (std::uint64_t k = 0; k < 150; ++k, ++next_step) {
      input.on_sample(state(1, next_step, next_step + 1, static_cast<double>(next_step)));
    }
    clock.step = next_step - 40;  // the newest 39 samples are not readable yet
    for (const idl::RobotState& s : input.take_new(1)) {
      ASSERT_DOUBLE_EQ(s.x(), static_cast<double>(next_x++));
    }
    ASSERT_EQ(next_x, clock.step + 1);
  }
  clock.step = next_step;
  for (const idl::RobotState& s : input.take_new(1)) {
    ASSERT_DOUBLE_EQ(s.x(), static_cast<double>(next_x++));
  }
  EXPECT_EQ(next_x, next_step);
}

// One call for many keys (the evaluator's recorders): the same samples in the same order as one
// take_new() per key, robot by robot in the order asked for.
TEST_F(InputTest, TakeNewOfManyKeysIsEachKeyInTurn) {
  detail::InputOptions options;
  options.expected = {3, 1, 2};
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, options);
  for (std::uint64_t step = 0; step < 3; ++step) {
    for (std::uint32_t robot : {2u, 3u, 1u}) {
      input.on_sample(state(robot, step, step + 1, 10.0 * robot + static_cast<double>(step)));
    }
  }
  clock.step = 1;
  std::vector<idl::RobotState> out;
  input.take_new({3, 1, 7}, out);  // 7: no such instance
  ASSERT_EQ(out.size(), 4u);
  EXPECT_DOUBLE_EQ(out[0].x(), 30.0);
  EXPECT_DOUBLE_EQ(out[1].x(), 31.0);
  EXPECT_DOUBLE_EQ(out[2].x(), 10.0);
  EXPECT_DOUBLE_EQ(out[3].x(), 11.0);
  input.take_new({2}, out);  // appended
  ASSERT_EQ(out.size(), 6u);
  EXPECT_DOUBLE_EQ(out[5].x(), 21.0);
  EXPECT_EQ(input.instances(), (std::vector<std::uint64_t>{1, 2, 3}));
}

TEST_F(InputTest, TakeNewOfManyRobotsIsEachRobotInStepOrder) {
  detail::InputOptions options;
  options.expected = {1, 2};
  options.by_robot = true;
  options.key_names = "robot_id, target_id";
  Input<idl::RangeMeasurement> input("sensor/range", "test", &clock, &notifier, options);
  input.on_sample(range(2, 5, 0, 1, 20.0));
  input.on_sample(range(1, 9, 0, 1, 10.0));  // robot 1's higher target first, at the earlier step
  input.on_sample(range(1, 3, 1, 2, 11.0));
  input.on_sample(range(2, 5, 1, 2, 21.0));
  clock.step = 1;
  std::vector<idl::RangeMeasurement> out;
  input.take_new_of_robots({2, 1}, out);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_DOUBLE_EQ(out[0].range(), 20.0);
  EXPECT_DOUBLE_EQ(out[1].range(), 21.0);
  EXPECT_DOUBLE_EQ(out[2].range(), 10.0);
  EXPECT_DOUBLE_EQ(out[3].range(), 11.0);
}

TEST_F(InputTest, NonFiniteSampleAdvancesTimeButIsDropped) {
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, robot_one(0));
  input.on_sample(state(1, 0, 1, 1.0));
  input.on_sample(state(1, 1, 2, std::numeric_limits<double>::quiet_NaN()));
  clock.step = 1;
  EXPECT_TRUE(input.ready(1, nullptr));
  ASSERT_NE(input.latest(1), nullptr);
  EXPECT_DOUBLE_EQ(input.latest(1)->x(), 1.0);
  EXPECT_EQ(input.rejected_count(), 1u);
  const InputCounts counts = input.counts();
  EXPECT_EQ(counts.accepted, 1u);
  EXPECT_EQ(counts.rejected.at("non_finite"), 1u);
}

// A co-located delivery shares SampleMeta::checks_passed among a sample's readers: in lockstep a
// reader whose checks pass sets it, and a reader that finds it set does not check again (here a
// NaN the flag vouches for is taken, which a real delivery never does: it shows the check is not
// run twice). Unset, or in real time, every reader checks.
TEST_F(InputTest, LockstepReadersOfOneDeliveryCheckASampleOnce) {
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, robot_one(0));
  bool passed = false;
  SampleMeta meta;
  meta.checks_passed = &passed;
  input.on_sample(state(1, 0, 1, 1.0), meta);
  EXPECT_TRUE(passed) << "a valid sample sets the flag for the next readers";
  passed = false;
  input.on_sample(state(1, 1, 2, std::numeric_limits<double>::quiet_NaN()), meta);
  EXPECT_FALSE(passed) << "a refused sample leaves it unset";
  EXPECT_EQ(input.counts().rejected.at("non_finite"), 1u);
  passed = true;
  input.on_sample(state(1, 2, 3, std::numeric_limits<double>::quiet_NaN()), meta);
  EXPECT_EQ(input.counts().accepted, 2u) << "checks passed by another reader are not run again";

  clock.mode = TimeMode::kRealtime;
  Input<idl::RobotState> realtime("plant/state", "test", &clock, &notifier, robot_one(0));
  passed = true;
  realtime.on_sample(state(1, 0, 1, std::numeric_limits<double>::quiet_NaN()), meta);
  EXPECT_EQ(realtime.counts().accepted, 0u) << "in real time the checks read the clock: each reader runs them";
}

TEST_F(InputTest, AgeIsMeasuredFromTheReceiveTimeOfTheNewestAcceptedSample) {
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, robot_one(0));
  EXPECT_FALSE(input.age_s(1, 5'000'000'000).has_value());  // nothing received
  input.on_sample(state(1, 0, 1, 1.0), SampleMeta{7, 1'000'000'000});
  // A rejected sample received later does not make the instance fresh again.
  input.on_sample(state(1, 1, 2, std::numeric_limits<double>::quiet_NaN()), SampleMeta{7, 4'000'000'000});
  ASSERT_TRUE(input.age_s(1, 5'000'000'000).has_value());
  EXPECT_DOUBLE_EQ(*input.age_s(1, 5'000'000'000), 4.0);
  EXPECT_TRUE(input.fresh(1, 4.0, 5'000'000'000));
  EXPECT_FALSE(input.fresh(1, 3.9, 5'000'000'000));
  EXPECT_FALSE(input.fresh(2, 100.0, 5'000'000'000)) << "an instance never received is not fresh";
  EXPECT_FALSE(input.age_s(2, 5'000'000'000).has_value());
}

TEST_F(InputTest, IgnoresUnexpectedInstances) {
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, robot_one(0));
  input.on_sample(state(5, 0, 1, 1.0));
  EXPECT_TRUE(input.instances().empty());
}

TEST_F(InputTest, RealtimeIsAlwaysReadyAndReadsTheNewest) {
  clock.mode = TimeMode::kRealtime;
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, robot_one(1));
  EXPECT_TRUE(input.ready(100, nullptr));
  input.on_sample(state(1, 7, 8, 3.0));
  ASSERT_NE(input.latest(1), nullptr);
  EXPECT_DOUBLE_EQ(input.latest(1)->x(), 3.0);
}

TEST_F(InputTest, RealtimeRefusesStampsInTheFutureOrNegativeWithoutOverflow) {
  clock.mode = TimeMode::kRealtime;
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, robot_one(0));
  const std::int64_t now = wall_clock_now_ns();
  auto stamped = [](std::uint64_t step, std::int64_t stamp_ns) {
    idl::RobotState s = state(1, step, step + 1, 1.0);
    s.header().stamp_ns(stamp_ns);
    return s;
  };
  input.on_sample(stamped(0, std::numeric_limits<std::int64_t>::max()), SampleMeta{3, 1'000});
  input.on_sample(stamped(1, std::numeric_limits<std::int64_t>::min()), SampleMeta{3, 2'000});
  input.on_sample(stamped(2, -1), SampleMeta{3, 3'000});
  input.on_sample(stamped(3, now + 60'000'000'000), SampleMeta{3, 4'000});  // a minute ahead
  EXPECT_EQ(input.latest(1), nullptr);
  EXPECT_FALSE(input.age_s(1, 10'000).has_value()) << "a refused sample is not fresh";
  input.on_sample(stamped(4, now), SampleMeta{3, 5'000});
  input.on_sample(stamped(5, now + 500'000'000), SampleMeta{3, 6'000});  // within the tolerance
  const InputCounts counts = input.counts();
  EXPECT_EQ(counts.accepted, 2u);
  EXPECT_EQ(counts.rejected.at("stamp_in_future"), 2u);
  EXPECT_EQ(counts.rejected.at("negative_stamp"), 2u);
  EXPECT_DOUBLE_EQ(*input.age_s(1, 10'000), 4e-6);
}

TEST_F(InputTest, LockstepStampsAreSimTimeOnlyNegativeIsRefused) {
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, robot_one(0));
  idl::RobotState far = state(1, 0, 1, 1.0);
  far.header().stamp_ns(std::numeric_limits<std::int64_t>::max());  // a long simulation, not absurd
  input.on_sample(far);
  idl::RobotState negative = state(1, 1, 2, 1.0);
  negative.header().stamp_ns(std::numeric_limits<std::int64_t>::min());
  input.on_sample(negative);
  const InputCounts counts = input.counts();
  EXPECT_EQ(counts.accepted, 1u);
  EXPECT_EQ(counts.rejected.at("negative_stamp"), 1u);
}

TEST_F(InputTest, AppliesThePlausibilityChecksOfTheTopicType) {
  detail::InputOptions options = robot_one(0);
  Input<idl::VelocityCommand> input("plant/cmd", "test", &clock, &notifier, options);
  idl::VelocityCommand cmd;
  cmd.robot_id(1);
  cmd.header().next_step(1);
  cmd.mode(static_cast<idl::CommandMode>(7));
  input.on_sample(cmd);
  cmd.mode(idl::VELOCITY);
  cmd.v(1e300);
  input.on_sample(cmd);
  cmd.v(0.5);
  input.on_sample(cmd);
  const InputCounts counts = input.counts();
  EXPECT_EQ(counts.accepted, 1u);
  EXPECT_EQ(counts.rejected.at("bad_enum"), 1u);
  EXPECT_EQ(counts.rejected.at("absurd_magnitude"), 1u);
  ASSERT_NE(input.latest(1), nullptr);
  EXPECT_DOUBLE_EQ(input.latest(1)->v(), 0.5);
}

/// Options of robot 1's input whose writers are named "writer-<id>".
detail::InputOptions named_writers() {
  detail::InputOptions options = robot_one(0);
  options.writer_name = [](std::uint64_t id) { return "writer-" + std::to_string(id); };
  return options;
}

TEST_F(InputTest, LockstepSecondProducerOfAnInstanceEndsTheRunNamingTopicInstanceAndBothWriters) {
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, named_writers());
  input.on_sample(state(1, 0, 1, 1.0), SampleMeta{7, 0});
  input.on_sample(state(1, 1, 2, 2.0), SampleMeta{7, 0});
  EXPECT_TRUE(input.ready(1, nullptr));
  EXPECT_TRUE(input.lockstep_error().empty());
  input.on_sample(state(1, 0, 1, 9.0), SampleMeta{8, 0});  // a restarted producer replays step 0
  try {
    input.ready(1, nullptr);
    FAIL() << "expected a RunError";
  } catch (const RunError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("plant/state"), std::string::npos) << what;
    EXPECT_NE(what.find("robot_id=1"), std::string::npos) << what;
    EXPECT_NE(what.find("writer-7"), std::string::npos) << what;
    EXPECT_NE(what.find("writer-8"), std::string::npos) << what;
  }
  EXPECT_EQ(input.counts().rejected.at(detail::kRejectSecondProducer), 1U);
  clock.step = 1;
  EXPECT_EQ(input.take_new(1).size(), 2U);  // the second writer's sample was not used
}

TEST_F(InputTest, OtherInstancesMayHaveOtherProducers) {
  detail::InputOptions options = named_writers();
  options.expected = {1, 2};
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, options);
  input.on_sample(state(1, 0, 1, 1.0), SampleMeta{7, 0});
  input.on_sample(state(2, 0, 1, 1.0), SampleMeta{8, 0});
  EXPECT_TRUE(input.ready(0, nullptr));
  EXPECT_TRUE(input.lockstep_error().empty());
}

TEST_F(InputTest, RealtimeFirstWriterWinsAndTheSecondIsCountedAsSecondProducer) {
  clock.mode = TimeMode::kRealtime;
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, named_writers());
  input.on_sample(state(1, 0, 1, 1.0), SampleMeta{7, 1'000'000'000});
  input.on_sample(state(1, 1, 2, 5.0), SampleMeta{8, 1'100'000'000});
  input.on_sample(state(1, 2, 3, 6.0), SampleMeta{8, 1'200'000'000});
  input.on_sample(state(1, 3, 4, 2.0), SampleMeta{7, 1'300'000'000});
  EXPECT_TRUE(input.ready(3, nullptr));  // real time never throws: a warning and the rule
  ASSERT_NE(input.latest(1), nullptr);
  EXPECT_DOUBLE_EQ(input.latest(1)->x(), 2.0);
  EXPECT_EQ(input.counts().accepted, 2U);
  EXPECT_EQ(input.counts().rejected.at(detail::kRejectSecondProducer), 2U);
  // The first producer falls silent for longer than the lease: a restarted producer takes over.
  input.on_sample(state(1, 9, 10, 4.0), SampleMeta{8, 1'300'000'000 + detail::kProducerSilenceNs + 1});
  EXPECT_DOUBLE_EQ(input.latest(1)->x(), 4.0);
  input.on_sample(state(1, 10, 11, 3.0), SampleMeta{7, 2'400'000'000});  // now 7 is the second one
  EXPECT_DOUBLE_EQ(input.latest(1)->x(), 4.0);
  EXPECT_EQ(input.counts().rejected.at(detail::kRejectSecondProducer), 3U);
}

// Issue 24, finding 1: a writer whose samples all fail their checks claimed the instance, and
// the real producer was refused for good (its "silence" counted accepted samples only).
TEST_F(InputTest, RealtimeWriterOfRefusedSamplesClaimsNothing) {
  clock.mode = TimeMode::kRealtime;
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, named_writers());
  for (std::uint64_t step = 0; step < 40; ++step) {
    input.on_sample(state(1, step, step + 1, std::numeric_limits<double>::quiet_NaN()), SampleMeta{7, 1'000'000'000});
  }
  input.on_sample(state(1, 50, 51, 2.0), SampleMeta{8, 1'100'000'000});  // the real producer, 0.1 s later
  ASSERT_NE(input.latest(1), nullptr);
  EXPECT_DOUBLE_EQ(input.latest(1)->x(), 2.0);
  EXPECT_EQ(input.counts().accepted, 1U);
  EXPECT_EQ(input.counts().rejected.at(detail::kRejectNonFinite), 40U);
  EXPECT_EQ(input.counts().rejected.count(detail::kRejectSecondProducer), 0U);
  // Nor does a refused sample of another writer take the instance over after a silence.
  input.on_sample(state(1, 60, 61, std::numeric_limits<double>::quiet_NaN()), SampleMeta{7, 9'000'000'000});
  input.on_sample(state(1, 61, 62, 3.0), SampleMeta{8, 9'000'000'001});
  EXPECT_DOUBLE_EQ(input.latest(1)->x(), 3.0);
}

// Issue 24, finding 2: in a scenario run only the writer the scenario assigns may produce an
// instance, whether another started first or not.
TEST_F(InputTest, AScenarioRunRefusesAnUnassignedWriterEvenIfItCameFirst) {
  for (TimeMode mode : {TimeMode::kRealtime, TimeMode::kLockstep}) {
    clock.mode = mode;
    detail::InputOptions options = named_writers();
    options.producer_assigned = [](std::uint64_t writer, std::uint32_t robot) { return robot == 1 && writer == 8; };
    Input<idl::RobotState> input("plant/cmd", "test", &clock, &notifier, options);
    input.on_sample(state(1, 0, 1, 9.0), SampleMeta{7, 1'000'000'000});  // foreign, first
    input.on_sample(state(1, 0, 1, 2.0), SampleMeta{8, 1'100'000'000});  // the scenario's producer
    input.on_sample(state(1, 1, 2, 9.0), SampleMeta{7, 1'200'000'000});
    EXPECT_TRUE(input.lockstep_error().empty()) << "a refused foreign writer is no second producer";
    ASSERT_NE(input.latest(1), nullptr);
    EXPECT_DOUBLE_EQ(input.latest(1)->x(), 2.0);
    EXPECT_EQ(input.counts().accepted, 1U);
    EXPECT_EQ(input.counts().rejected.at(detail::kRejectUnknownProducer), 2U);
  }
}

// Issue 24, finding 2: a mission is sent once, so its producer always looked "silent" and any
// later writer took it over.
TEST_F(InputTest, ASendOnceTopicsProducerIsNeverSilent) {
  clock.mode = TimeMode::kRealtime;
  detail::InputOptions options = named_writers();
  options.send_once = true;
  Input<idl::RobotState> input("mission/waypoints", "test", &clock, &notifier, options);
  input.on_sample(state(1, 0, kNeverAgain, 1.0), SampleMeta{7, 1'000'000'000});
  input.on_sample(state(1, 0, kNeverAgain, 5.0), SampleMeta{8, 60'000'000'000});  // a minute later
  EXPECT_DOUBLE_EQ(input.latest(1)->x(), 1.0);
  EXPECT_EQ(input.counts().rejected.at(detail::kRejectSecondProducer), 1U);
}

// Issue 24, finding 4: samples of robots the scenario does not have are refused and counted, and
// leave no per-instance state behind (a flood of keys).
TEST_F(InputTest, KeysOfRobotsOutsideTheScenarioAreRefusedWithoutState) {
  clock.mode = TimeMode::kRealtime;
  detail::InputOptions options;
  options.key_names = "robot_id";
  options.known_robots = {1, 2};
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, options);  // any instance
  for (std::uint32_t robot = 3; robot < 20003; ++robot) {
    input.on_sample(state(robot, 0, 1, 1.0), SampleMeta{7, 1'000'000'000});
  }
  input.on_sample(state(2, 0, 1, 1.0), SampleMeta{8, 1'000'000'000});
  EXPECT_EQ(input.instances(), (std::vector<std::uint64_t>{2}));
  EXPECT_EQ(input.counts().accepted, 1U);
  EXPECT_EQ(input.counts().rejected.at(detail::kRejectUnknownKey), 20000U);
}

// The same rule as a transport's key filter asks it (Bus::KeyFilter): which keys the input takes,
// and the samples the transport dropped counted as if they had arrived.
TEST_F(InputTest, TheKeyRuleForTheTransportMatchesStoreAndCountsWhatItDropped) {
  clock.mode = TimeMode::kRealtime;
  detail::InputOptions options;
  options.key_names = "robot_id, peer_id";
  options.known_robots = {1, 2};
  Input<idl::RobotState> input("sensor/uwb", "test", &clock, &notifier, options);
  EXPECT_TRUE(input.filters_keys());
  EXPECT_TRUE(input.takes_key(std::uint64_t{2} << 32 | 7));
  EXPECT_FALSE(input.takes_key(std::uint64_t{3} << 32 | 1));
  testing::internal::CaptureStderr();
  input.count_unknown_key(std::uint64_t{3} << 32 | 1, 0);
  input.count_unknown_key(std::uint64_t{4} << 32 | 1, 0);
  const std::string log = testing::internal::GetCapturedStderr();
  EXPECT_NE(log.find("rejected a sample on sensor/uwb from an unnamed writer (key 12884901889)"), std::string::npos) << log;
  EXPECT_EQ(log.find("rejected", log.find("rejected") + 1), std::string::npos) << "logged once: " << log;
  EXPECT_EQ(input.counts().rejected.at(detail::kRejectUnknownKey), 2U);
  EXPECT_TRUE(input.instances().empty());
  // Host-level and unkeyed inputs, and inputs without a scenario's robots, take every key.
  detail::InputOptions host = options;
  host.ignore_step = true;
  EXPECT_FALSE(Input<idl::RobotState>("sim/clock", "test", &clock, &notifier, host).filters_keys());
  detail::InputOptions unkeyed = options;
  unkeyed.key_names = "-";
  EXPECT_FALSE(Input<idl::RobotState>("run/health", "test", &clock, &notifier, unkeyed).filters_keys());
  detail::InputOptions standalone = options;
  standalone.known_robots.clear();
  EXPECT_FALSE(Input<idl::RobotState>("plant/state", "test", &clock, &notifier, standalone).filters_keys());
}

TEST_F(InputTest, ExclusiveOwnershipMakesAChangeOfWriterAHandOver) {
  clock.mode = TimeMode::kRealtime;
  detail::InputOptions options = named_writers();
  options.exclusive_ownership = true;
  Input<idl::RobotState> input("estimate/pose", "test", &clock, &notifier, options);
  input.on_sample(state(1, 0, 1, 1.0), SampleMeta{7, 1'000'000'000});
  input.on_sample(state(1, 1, 2, 5.0), SampleMeta{8, 1'100'000'000});  // the middleware chose 8
  ASSERT_NE(input.latest(1), nullptr);
  EXPECT_DOUBLE_EQ(input.latest(1)->x(), 5.0);
  EXPECT_EQ(input.counts().rejected_total(), 0U);
}

TEST_F(InputTest, TwoWritersOfOneInstanceOnABusAreTwoProducersNamedByTheBus) {
  // End to end through a bus: SampleMeta from the MemoryBus (one id per writer handle), names
  // from Bus::writer_name. Two profiles give two writers of plant/state, as two processes would.
  MemoryBus bus;
  detail::InputOptions options = robot_one(0);
  options.writer_name = [&bus](std::uint64_t id) { return bus.writer_name(id); };
  Input<idl::RobotState> input("plant/state", "test", &clock, &notifier, options);
  auto reader = bus.reader("plant/state", idl::type_name<idl::RobotState>(), "state",
                           [&input](const void* sample, const SampleMeta& meta) {
                             input.on_sample(*static_cast<const idl::RobotState*>(sample), meta);
                           },
                           nullptr);
  auto first = bus.writer("plant/state", idl::type_name<idl::RobotState>(), "state");
  auto second = bus.writer("plant/state", idl::type_name<idl::RobotState>(), "lockstep");
  idl::RobotState sample = state(1, 0, 1, 1.0);
  first->write(&sample);
  EXPECT_TRUE(input.ready(0, nullptr));
  second->write(&sample);
  EXPECT_THROW(input.ready(0, nullptr), RunError);
  const std::string conflict = input.lockstep_error();
  EXPECT_NE(conflict.find("(plant/state|state)"), std::string::npos) << conflict;
  EXPECT_NE(conflict.find("(plant/state|lockstep)"), std::string::npos) << conflict;
}

}  // namespace
}  // namespace robodds
