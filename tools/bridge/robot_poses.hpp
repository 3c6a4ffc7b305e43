#pragma once
// `robodds bridge --foxglove-scene`: the robots' latest poses as one foxglove.PosesInFrame message
// (Foxglove's well-known schema, JSON encoding), which Foxglove's 3D panel draws without any
// configuration. Plain C++, no sockets, no DDS: the command feeds it the plant/state samples.

#include <cstdint>
#include <map>
#include <string>

namespace robodds::bridge {

/// The derived channel's topic, schema name and JSON Schema text.
inline constexpr const char* kRobotPosesTopic = "foxglove/robot_poses";
inline constexpr const char* kPosesInFrameSchemaName = "foxglove.PosesInFrame";
std::string poses_in_frame_json_schema();

class RobotPoses {
 public:
  /// The robot's pose (m, m, rad) in the world frame, from its newest state sample.
  void update(std::uint32_t robot_id, double x, double y, double theta);
  /// A foxglove.PosesInFrame message: timestamp `stamp_ns`, frame "world", every robot seen so far
  /// in robot id order (z = 0, orientation the rotation by theta about z).
  std::string json(std::int64_t stamp_ns) const;

 private:
  struct Pose {
    double x = 0, y = 0, theta = 0;
  };
  std::map<std::uint32_t, Pose> robots_;
};

}  // namespace robodds::bridge
