#include "runtime/bus/sample_key.hpp"

#include <gtest/gtest.h>

#include "robodds/idl/robodds.h"

namespace robodds {
namespace {

TEST(SampleKeyFunction, IsTheInputsInstanceKeyOfTheNamedType) {
  const SampleKeyFunction robot_key = sample_key_function("robodds::idl::RobotState");
  ASSERT_NE(robot_key, nullptr);
  idl::RobotState state;
  state.robot_id(7);
  EXPECT_EQ(robot_key(&state), 7u);

  const SampleKeyFunction pair_key = sample_key_function("robodds::idl::UwbRanges");
  ASSERT_NE(pair_key, nullptr);
  idl::UwbRanges ranges;
  ranges.robot_id(2);
  ranges.peer_id(3);
  EXPECT_EQ(pair_key(&ranges), (std::uint64_t{2} << 32) | 3u) << "robot_id in the high half, peer_id in the low";
}

TEST(SampleKeyFunction, NullForAnUnknownType) { EXPECT_EQ(sample_key_function("robodds::idl::NoSuchType"), nullptr); }

TEST(SampleStepsFunction, IsTheHeadersStepAndNextStep) {
  const SampleStepsFunction steps = sample_steps_function("robodds::idl::RobotState");
  ASSERT_NE(steps, nullptr);
  idl::RobotState state;
  state.header().step(40);
  state.header().next_step(50);
  EXPECT_EQ(steps(&state).step, 40u);
  EXPECT_EQ(steps(&state).next_step, 50u);
  EXPECT_EQ(sample_steps_function("robodds::idl::NoSuchType"), nullptr);
}

}  // namespace
}  // namespace robodds
