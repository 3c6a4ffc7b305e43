#include "system/foxglove/robot_poses.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

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
