// SceneFeed: every plant/state payload updates the poses, and the scene (foxglove.PosesInFrame
// JSON) is due at most once per foxglove::kScenePeriodNs of the samples' stamps, however many
// robots send: what `robodds bridge --foxglove-scene` sends and `robodds record --foxglove-scene`
// writes.
#include "tools/robodds/scene_source.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "robodds/idl/robodds.h"
#include "runtime/bus/sample_codec.hpp"
#include "runtime/dds/dds_sample_codec.hpp"

namespace robodds {
namespace {

using nlohmann::json;

class SceneFeedTest : public ::testing::Test {
 protected:
  void SetUp() override { set_sample_codec(make_dds_sample_codec()); }
  void TearDown() override { set_sample_codec(nullptr); }

  static std::vector<std::uint8_t> state_payload(std::uint32_t robot, double x) {
    idl::RobotState state;
    state.robot_id(robot);
    state.x(x);
    state.y(-x);
    state.theta(0.0);
    return sample_codec().serialize(idl::type_name<idl::RobotState>(), &state);
  }
};

TEST_F(SceneFeedTest, TwoHundredRobotsAtOneHundredHzGiveTwentyScenesPerSecondOfStamps) {
  SceneFeed feed("test");
  constexpr std::uint32_t kRobots = 200;
  constexpr std::int64_t kStepNs = 10'000'000;  // 100 Hz
  std::vector<json> sent;
  std::vector<std::int64_t> sent_step;
  for (std::int64_t step = 0; step < 100; ++step) {  // 1 s of stamps, every robot's state each step
    for (std::uint32_t robot = 0; robot < kRobots; ++robot) {
      const auto payload = state_payload(robot, static_cast<double>(step));
      if (const std::optional<std::string> text = feed.take(payload.data(), payload.size(), step * kStepNs)) {
        sent.push_back(json::parse(*text));
        sent_step.push_back(step);
      }
    }
  }
  // One at the first stamp, then one per 50 ms: 0, 50, ..., 950 ms (not 20,000 of them).
  ASSERT_EQ(sent.size(), 20u);
  for (std::size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(sent_step[i], static_cast<std::int64_t>(i) * 5);
  }
  // Stamped as the sample that made it due; the poses were updated from every sample in between:
  // the first robot of the step sent it, the others still at the step before.
  const json& last = sent.back();
  EXPECT_EQ(last["timestamp"]["sec"], 0);
  EXPECT_EQ(last["timestamp"]["nsec"], 950'000'000);
  ASSERT_EQ(last["poses"].size(), kRobots);
  EXPECT_EQ(last["poses"][0]["position"]["x"], 95.0);
  EXPECT_EQ(last["poses"][1]["position"]["x"], 94.0);
  EXPECT_EQ(last["poses"][199]["position"]["x"], 94.0);
  EXPECT_EQ(last["poses"][199]["position"]["y"], -94.0);
}

TEST_F(SceneFeedTest, APayloadThatDoesNotDecodeSendsNothingAndUsesNoPeriod) {
  SceneFeed feed("test");
  const std::vector<std::uint8_t> garbage = {0x01, 0x02, 0x03};
  EXPECT_FALSE(feed.take(garbage.data(), garbage.size(), 0));
  const auto payload = state_payload(7, 1.5);
  const std::optional<std::string> text = feed.take(payload.data(), payload.size(), 0);
  ASSERT_TRUE(text) << "the first good sample is due";
  const json m = json::parse(*text);
  ASSERT_EQ(m["poses"].size(), 1u);
  EXPECT_EQ(m["poses"][0]["position"]["x"], 1.5);
}

}  // namespace
}  // namespace robodds
