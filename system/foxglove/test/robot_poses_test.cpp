#include "system/foxglove/robot_poses.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <string>

namespace robodds::foxglove {
namespace {

using nlohmann::json;

TEST(FoxgloveRobotPoses, OnePosesInFrameOfEveryRobotInIdOrderWithItsHeadingAsAQuaternion) {
  RobotPoses poses;
  poses.update(2, 5.0, 0.0, M_PI / 2);
  poses.update(1, 1.0, 2.0, 0.0);
  poses.update(1, 1.5, 2.5, M_PI);  // the newest counts
  const json m = json::parse(poses.json(1'700'000'000'123'456'789));
  EXPECT_EQ(m["timestamp"]["sec"], 1'700'000'000);
  EXPECT_EQ(m["timestamp"]["nsec"], 123'456'789);
  EXPECT_EQ(m["frame_id"], "world");
  ASSERT_EQ(m["poses"].size(), 2u);
  EXPECT_EQ(m["poses"][0]["position"], json::parse(R"({"x":1.5,"y":2.5,"z":0.0})"));
  EXPECT_NEAR(m["poses"][0]["orientation"]["z"].get<double>(), 1.0, 1e-12);  // pi about z
  EXPECT_NEAR(m["poses"][0]["orientation"]["w"].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(m["poses"][1]["orientation"]["z"].get<double>(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(m["poses"][1]["orientation"]["w"].get<double>(), std::sqrt(0.5), 1e-12);
}

/// The message built afresh, as json() did before it reused its message: the bytes must not change.
std::string built_afresh(const std::map<std::uint32_t, std::array<double, 3>>& robots, std::int64_t stamp_ns) {
  json poses = json::array();
  for (const auto& [id, p] : robots) {
    poses.push_back({{"position", {{"x", p[0]}, {"y", p[1]}, {"z", 0.0}}},
                     {"orientation", {{"x", 0.0}, {"y", 0.0}, {"z", std::sin(p[2] / 2)}, {"w", std::cos(p[2] / 2)}}}});
  }
  return json{{"timestamp", {{"sec", stamp_ns / 1000000000}, {"nsec", stamp_ns % 1000000000}}}, {"frame_id", "world"}, {"poses", poses}}
      .dump();
}

TEST(FoxgloveRobotPoses, TheReusedMessageHasTheBytesOfOneBuiltAfreshAsRobotsComeAndMove) {
  RobotPoses poses;
  std::map<std::uint32_t, std::array<double, 3>> robots;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mantissa(-1000.0, 1000.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  for (int k = 0; k < 2000; ++k) {
    const auto id = static_cast<std::uint32_t>(rng() % 40);  // new robots now and then, mostly moves
    const std::array<double, 3> p{mantissa(rng) * std::pow(10.0, exponent(rng)), mantissa(rng), mantissa(rng) / 100};
    robots[id] = p;
    poses.update(id, p[0], p[1], p[2]);
    const auto stamp = static_cast<std::int64_t>(rng() % 4'000'000'000'000'000'000ULL);
    ASSERT_EQ(poses.json(stamp), built_afresh(robots, stamp)) << "update " << k << " (robot " << id << ")";
  }
}

TEST(FoxgloveRobotPoses, TheSchemaIsFoxglovesPosesInFrame) {
  const json schema = json::parse(poses_in_frame_json_schema());
  EXPECT_EQ(schema["title"], "foxglove.PosesInFrame");
  EXPECT_EQ(schema["properties"]["poses"]["items"]["properties"]["orientation"]["properties"].size(), 4u);
  EXPECT_EQ(std::string(kPosesInFrameSchemaName), "foxglove.PosesInFrame");
}

TEST(FoxgloveRobotPoses, DueOnTheFirstStampThenOncePerPeriodOfTheStamps) {
  RobotPoses poses;
  constexpr std::int64_t kPeriod = 50'000'000;  // 50 ms
  EXPECT_TRUE(poses.due(1'000'000'000, kPeriod));
  EXPECT_FALSE(poses.due(1'000'000'000, kPeriod));  // the same step's other robots
  EXPECT_FALSE(poses.due(1'040'000'000, kPeriod));
  EXPECT_TRUE(poses.due(1'050'000'000, kPeriod));
  EXPECT_FALSE(poses.due(1'090'000'000, kPeriod));
  EXPECT_TRUE(poses.due(1'130'000'000, kPeriod));  // counted from the last true, not a grid
}

}  // namespace
}  // namespace robodds::foxglove
