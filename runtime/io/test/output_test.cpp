// Output: the header stamps and which instances it tells its writer have ended
// (InstanceEnds::kForgotten; WriterHandle::end_instance), without DDS.
#include "runtime/io/io.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace robodds {
namespace {

/// Records what an Output hands its writer: each write and each ended instance, as keys.
class RecordingWriter : public WriterHandle {
 public:
  void write(const void* sample) override { written.push_back(key(sample)); }
  void end_instance(const void* sample) override { ended.push_back(key(sample)); }
  const std::string& topic() const override { return topic_; }

  std::vector<std::uint64_t> written;
  std::vector<std::uint64_t> ended;

 private:
  static std::uint64_t key(const void* sample) { return idl::instance_key(*static_cast<const idl::RangeMeasurement*>(sample)); }
  std::string topic_ = "sensor/range";
};

std::uint64_t key_of(std::uint32_t robot, std::uint32_t target) { return (std::uint64_t(robot) << 32) | target; }

class OutputTest : public ::testing::Test {
 protected:
  /// Publishes robot `robot`'s range to `target` at `step`, due again at the next step.
  void publish(Output<idl::RangeMeasurement>& out, std::uint64_t step, std::uint32_t robot, std::uint32_t target) {
    state.step = step;
    idl::RangeMeasurement m;
    m.robot_id(robot);
    m.target_id(target);
    m.range(100.0);
    out.publish(m);
  }

  StepState state;
  std::shared_ptr<RecordingWriter> writer = std::make_shared<RecordingWriter>();
};

TEST_F(OutputTest, StampsStepNextStepAndTime) {
  Output<idl::RangeMeasurement> out(writer, &state);
  state.step = 7;
  state.period_steps = 5;
  state.stamp_ns = 140'000'000;
  idl::RangeMeasurement m;
  out.publish(m);
  EXPECT_EQ(m.header().step(), 7u);
  EXPECT_EQ(m.header().next_step(), 12u);
  EXPECT_EQ(m.header().stamp_ns(), 140'000'000);
  out.publish_final(m);
  EXPECT_EQ(m.header().next_step(), kNeverAgain);
}

TEST_F(OutputTest, AStreamWrittenAtEveryDueStepNeverEnds) {
  Output<idl::RangeMeasurement> out(writer, &state, InstanceEnds::kForgotten);
  for (std::uint64_t step = 0; step < 100; ++step) {
    publish(out, step, 1, 1);
    publish(out, step, 2, 1);
  }
  EXPECT_TRUE(writer->ended.empty());
  EXPECT_EQ(out.ended_instances(), 0u);
}

TEST_F(OutputTest, AFinalSampleEndsItsInstanceAtOnce) {
  Output<idl::RangeMeasurement> out(writer, &state, InstanceEnds::kForgotten);
  publish(out, 0, 4, 1);
  idl::RangeMeasurement last;
  last.robot_id(4);
  last.target_id(1);
  state.step = 1;
  out.publish_final(last);
  ASSERT_EQ(writer->ended.size(), 1u);
  EXPECT_EQ(writer->ended[0], key_of(4, 1));
  // Nothing is ended twice, however long the others go on.
  for (std::uint64_t step = 2; step < 50; ++step) {
    publish(out, step, 1, 1);
  }
  EXPECT_EQ(writer->ended.size(), 1u);
}

TEST_F(OutputTest, LockstepAnInstanceWhoseDueStepPassedWithoutASampleEnds) {
  Output<idl::RangeMeasurement> out(writer, &state, InstanceEnds::kForgotten);
  for (std::uint64_t step = 0; step < 10; ++step) {
    publish(out, step, 1, 1);  // robot 1 to target 1 until step 9 (due at 10)
  }
  publish(out, 10, 1, 2);  // at 10 robot 1 moves to target 2: (1, 1) was due at 10 and got nothing
  EXPECT_TRUE(writer->ended.empty()) << "the step of the switch is not over yet";
  publish(out, 11, 1, 2);
  ASSERT_EQ(writer->ended.size(), 1u);
  EXPECT_EQ(writer->ended[0], key_of(1, 1));
  // Coming back to target 1 writes that instance again and it is live again.
  publish(out, 12, 1, 1);
  publish(out, 13, 1, 1);
  ASSERT_EQ(writer->ended.size(), 2u);
  EXPECT_EQ(writer->ended[1], key_of(1, 2));
  EXPECT_EQ(out.ended_instances(), 2u);
}

TEST_F(OutputTest, AnInstanceAnnouncedLaterIsNotEndedBeforeItsStep) {
  Output<idl::RangeMeasurement> out(writer, &state, InstanceEnds::kForgotten);
  state.step = 0;
  idl::RangeMeasurement m;
  m.robot_id(1);
  m.target_id(1);
  out.publish_next_at(m, 5);  // its samples of steps 1-4 are lost: the next comes at 5
  for (std::uint64_t step = 1; step < 5; ++step) {
    publish(out, step, 2, 1);
  }
  state.step = 5;
  out.publish_next_at(m, 6);
  publish(out, 5, 2, 1);
  EXPECT_TRUE(writer->ended.empty()) << "(1, 1) came at the step it announced";
  publish(out, 6, 2, 1);
  publish(out, 7, 2, 1);
  ASSERT_EQ(writer->ended.size(), 1u) << "(1, 1) was due at 6 and is not written from then on";
  EXPECT_EQ(writer->ended[0], key_of(1, 1));
}

TEST_F(OutputTest, RealtimeAStreamEndsOnlyAfterItsGracePeriods) {
  state.mode = TimeMode::kRealtime;
  Output<idl::RangeMeasurement> out(writer, &state, InstanceEnds::kForgotten);
  publish(out, 0, 1, 1);  // due at 1, never written again
  std::uint64_t step = 1;
  for (; step <= kRealtimeEndGracePeriods + 1; ++step) {
    publish(out, step, 2, 1);
  }
  EXPECT_TRUE(writer->ended.empty()) << "a late real-time loop is not an ended stream";
  publish(out, step, 2, 1);
  ASSERT_EQ(writer->ended.size(), 1u);
  EXPECT_EQ(writer->ended[0], key_of(1, 1));
}

TEST_F(OutputTest, RealtimeSkippedStepsOfTheWholeComponentEndNothing) {
  state.mode = TimeMode::kRealtime;
  Output<idl::RangeMeasurement> out(writer, &state, InstanceEnds::kForgotten);
  publish(out, 0, 1, 1);
  publish(out, 0, 2, 1);
  publish(out, 200, 1, 1);  // the loop stalled for 200 steps; both robots are published again
  publish(out, 200, 2, 1);
  publish(out, 201, 1, 1);
  EXPECT_TRUE(writer->ended.empty());
}

TEST_F(OutputTest, KeptInstancesAreNeverEnded) {
  Output<idl::RangeMeasurement> out(writer, &state);  // e.g. a mission: its last sample stays for late joiners
  publish(out, 0, 1, 1);
  idl::RangeMeasurement m;
  m.robot_id(2);
  state.step = 1;
  out.publish_final(m);
  for (std::uint64_t step = 2; step < 10; ++step) {
    publish(out, step, 3, 1);
  }
  EXPECT_TRUE(writer->ended.empty());
}

}  // namespace
}  // namespace robodds
