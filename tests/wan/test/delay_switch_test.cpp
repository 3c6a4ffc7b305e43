#include "tests/wan/delay_switch.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace robodds::wan {
namespace {

std::vector<std::uint8_t> frame(std::uint8_t to, std::uint8_t from, std::uint8_t payload = 0) {
  // Locally administered unicast MACs 02:00:00:00:00:xx; 0xff.. is broadcast.
  std::vector<std::uint8_t> f(60, payload);
  for (int i = 0; i < 6; ++i) {
    f[i] = to == 0xff ? 0xff : (i == 0 ? 0x02 : (i == 5 ? to : 0));
    f[6 + i] = i == 0 ? 0x02 : (i == 5 ? from : 0);
  }
  return f;
}

DelaySwitchParams delay(double s, double loss = 0.0) {
  DelaySwitchParams p;
  p.delay_s = s;
  p.loss = loss;
  return p;
}

TEST(DelaySwitch, AFrameIsDeliveredOnlyAfterTheDelay) {
  DelaySwitch sw(2, delay(0.05));
  const auto f = frame(0xff, 1);
  sw.receive(0, f.data(), f.size(), 10.0);
  EXPECT_DOUBLE_EQ(sw.next_due_s(), 10.05);
  EXPECT_TRUE(sw.take_due(10.049).empty());
  const auto due = sw.take_due(10.05);
  ASSERT_EQ(due.size(), 1u);
  EXPECT_EQ(due[0].port, 1u);
  EXPECT_EQ(due[0].frame, f);
  EXPECT_LT(sw.next_due_s(), 0.0);
}

TEST(DelaySwitch, BroadcastFloodsAndLearnedUnicastGoesToOnePort) {
  DelaySwitch sw(3, delay(0.0));
  const auto hello = frame(0xff, 3);  // host on port 2 announces itself
  sw.receive(2, hello.data(), hello.size(), 0.0);
  auto due = sw.take_due(0.0);
  ASSERT_EQ(due.size(), 2u);
  EXPECT_EQ(due[0].port, 0u);
  EXPECT_EQ(due[1].port, 1u);
  const auto reply = frame(3, 1);  // to the learned MAC: port 2 only
  sw.receive(0, reply.data(), reply.size(), 0.0);
  due = sw.take_due(0.0);
  ASSERT_EQ(due.size(), 1u);
  EXPECT_EQ(due[0].port, 2u);
}

TEST(DelaySwitch, KeepsTheOrderOfFramesOnALink) {
  DelaySwitch sw(2, delay(0.01));
  for (std::uint8_t i = 0; i < 5; ++i) {
    const auto f = frame(0xff, 1, i);
    sw.receive(0, f.data(), f.size(), 0.001 * i);
  }
  const auto due = sw.take_due(1.0);
  ASSERT_EQ(due.size(), 5u);
  for (std::uint8_t i = 0; i < 5; ++i) EXPECT_EQ(due[i].frame.back(), i);
}

TEST(DelaySwitch, LosesAboutTheGivenFractionTheSameWayForTheSameSeed) {
  auto run = [](std::uint64_t seed) {
    auto p = delay(0.0, 0.1);
    p.seed = seed;
    DelaySwitch sw(2, p);
    std::vector<bool> delivered;
    for (int i = 0; i < 5000; ++i) {
      const auto f = frame(0xff, 1);
      sw.receive(0, f.data(), f.size(), 0.0);
      delivered.push_back(!sw.take_due(0.0).empty());
    }
    EXPECT_EQ(sw.counters(1).lost + sw.counters(1).frames_out, 5000u);
    EXPECT_NEAR(static_cast<double>(sw.counters(1).lost) / 5000.0, 0.1, 0.02);
    return delivered;
  };
  EXPECT_EQ(run(7), run(7));
  EXPECT_NE(run(7), run(8));
}

TEST(DelaySwitch, AFullQueueDropsAndCounts) {
  auto p = delay(1.0);
  p.max_queued_frames = 3;
  DelaySwitch sw(2, p);
  for (int i = 0; i < 5; ++i) {
    const auto f = frame(0xff, 1);
    sw.receive(0, f.data(), f.size(), 0.0);
  }
  EXPECT_EQ(sw.counters(1).overflowed, 2u);
  EXPECT_EQ(sw.take_due(1.0).size(), 3u);
  EXPECT_EQ(sw.counters(0).frames_in, 5u);
}

TEST(DelaySwitch, ARuntFrameIsCountedAndDropped) {
  DelaySwitch sw(2, delay(0.0));
  const std::uint8_t runt[4] = {1, 2, 3, 4};
  sw.receive(0, runt, sizeof runt, 0.0);
  EXPECT_EQ(sw.counters(0).frames_in, 1u);
  EXPECT_TRUE(sw.take_due(1.0).empty());
}

TEST(DelaySwitch, RejectsBadParametersNamingThem) {
  EXPECT_THROW(DelaySwitch(2, delay(-1.0)), std::invalid_argument);
  try {
    DelaySwitch(2, delay(0.0, 1.0));
    FAIL() << "loss 1 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("loss"), std::string::npos) << e.what();
  }
  EXPECT_THROW(DelaySwitch(1, delay(0.0)), std::invalid_argument);
  EXPECT_THROW(parse_non_negative("--delay-ms", "5x"), std::invalid_argument);
  EXPECT_THROW(parse_non_negative("--delay-ms", "-1"), std::invalid_argument);
  EXPECT_DOUBLE_EQ(parse_non_negative("--delay-ms", "12.5"), 12.5);
}

}  // namespace
}  // namespace robodds::wan
