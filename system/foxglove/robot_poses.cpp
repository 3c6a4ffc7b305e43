#include "system/foxglove/robot_poses.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

namespace robodds::foxglove {

using nlohmann::json;

std::string poses_in_frame_json_schema() {
  // The fields of foxglove.PosesInFrame robodds fills (Foxglove recognises the schema by its name).
  const json number = {{"type", "number"}};
  const json vector3 = {{"type", "object"}, {"properties", {{"x", number}, {"y", number}, {"z", number}}}};
  const json quaternion = {{"type", "object"}, {"properties", {{"x", number}, {"y", number}, {"z", number}, {"w", number}}}};
  const json time = {{"type", "object"},
                     {"properties", {{"sec", {{"type", "integer"}, {"minimum", 0}}},
                                     {"nsec", {{"type", "integer"}, {"minimum", 0}, {"maximum", 999999999}}}}}};
  return json{{"title", kPosesInFrameSchemaName},
              {"description", "An array of timestamped poses for an object or reference frame in 3D space"},
              {"type", "object"},
              {"properties",
               {{"timestamp", time},
                {"frame_id", {{"type", "string"}}},
                {"poses", {{"type", "array"},
                           {"items", {{"type", "object"}, {"properties", {{"position", vector3}, {"orientation", quaternion}}}}}}}}}}
      .dump();
}

std::uint16_t add_robot_poses_channel(mcap::Writer& writer) {
  const std::uint16_t schema = writer.add_schema(kPosesInFrameSchemaName, "jsonschema", poses_in_frame_json_schema());
  return writer.add_channel(schema, kRobotPosesTopic, "json");
}

RobotPoses::RobotPoses() = default;
RobotPoses::~RobotPoses() = default;
RobotPoses::RobotPoses(RobotPoses&&) noexcept = default;
RobotPoses& RobotPoses::operator=(RobotPoses&&) noexcept = default;

void RobotPoses::update(std::uint32_t robot_id, double x, double y, double theta) {
  const auto [it, added] = robots_.insert_or_assign(robot_id, Pose{x, y, theta});
  if (added) {
    message_.reset();  // one pose more: rebuilt by the next json()
  }
}

std::string RobotPoses::json(std::int64_t stamp_ns) {
  if (!message_) {
    nlohmann::json poses = nlohmann::json::array();
    for (std::size_t i = 0; i < robots_.size(); ++i) {
      poses.push_back({{"position", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}},
                       {"orientation", {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}, {"w", 0.0}}}});
    }
    message_ = std::make_unique<nlohmann::json>(nlohmann::json{
        {"timestamp", {{"sec", 0}, {"nsec", 0}}}, {"frame_id", "world"}, {"poses", std::move(poses)}});
  }
  nlohmann::json& m = *message_;
  m["timestamp"]["sec"] = stamp_ns / 1000000000;
  m["timestamp"]["nsec"] = stamp_ns % 1000000000;
  auto pose = m["poses"].begin();
  for (const auto& [id, p] : robots_) {
    nlohmann::json& position = (*pose)["position"];
    position["x"] = p.x;
    position["y"] = p.y;
    // A rotation by theta about z: (0, 0, sin(theta/2), cos(theta/2)).
    nlohmann::json& orientation = (*pose)["orientation"];
    orientation["z"] = std::sin(p.theta / 2);
    orientation["w"] = std::cos(p.theta / 2);
    ++pose;
  }
  return m.dump();
}

bool RobotPoses::due(std::int64_t stamp_ns, std::int64_t period_ns) {
  if (emitted_ && stamp_ns - last_emitted_ns_ < period_ns) {
    return false;
  }
  emitted_ = true;
  last_emitted_ns_ = stamp_ns;
  return true;
}

}  // namespace robodds::foxglove
