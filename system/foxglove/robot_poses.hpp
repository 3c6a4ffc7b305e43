#pragma once
// `--foxglove-scene` of `robodds bridge` and `robodds record`, `--record-foxglove-scene` of
// `robodds run`: the robots' latest poses as one foxglove.PosesInFrame message (Foxglove's
// well-known schema, JSON encoding), which Foxglove's 3D panel draws without any configuration.
// Plain C++, no sockets, no DDS: the commands feed it the robots' state samples.

#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "runtime/mcap/mcap_writer.hpp"

namespace robodds::foxglove {

/// The topic the robots' poses are drawn from (the plant's true states, idl::RobotState).
inline constexpr const char* kSceneSource = "plant/state";
/// At most one scene message per 50 ms of the samples' stamps (20 Hz: enough for a 3D view).
inline constexpr std::int64_t kScenePeriodNs = 50'000'000;

/// The derived channel's topic, schema name and JSON Schema text.
inline constexpr const char* kRobotPosesTopic = "foxglove/robot_poses";
inline constexpr const char* kPosesInFrameSchemaName = "foxglove.PosesInFrame";
std::string poses_in_frame_json_schema();

/// Adds the foxglove/robot_poses schema (jsonschema) and channel (json) to `writer`; its id.
std::uint16_t add_robot_poses_channel(mcap::Writer& writer);

class RobotPoses {
 public:
  RobotPoses();
  ~RobotPoses();
  RobotPoses(RobotPoses&&) noexcept;
  RobotPoses& operator=(RobotPoses&&) noexcept;

  /// The robot's pose (m, m, rad) in the world frame, from its newest state sample.
  void update(std::uint32_t robot_id, double x, double y, double theta);
  /// A foxglove.PosesInFrame message: timestamp `stamp_ns`, frame "world", every robot seen so far
  /// in robot id order (z = 0, orientation the rotation by theta about z). Not const: it fills the
  /// message it built for the robots seen (rebuilt when one is added) instead of building one per
  /// call, which took 3/4 of the time and more (200 robots: 0.12-0.13 against 0.50-0.79 ms per
  /// message, -O3; docs/performance.md, "The Foxglove scene in the run").
  std::string json(std::int64_t stamp_ns);
  /// True for the first stamp and then for each stamp at least `period_ns` after the last one it
  /// was true for: the recorder writes the scene at most once per period of the samples' own time
  /// (ns), so that a lockstep run gives the same messages however it is deployed.
  bool due(std::int64_t stamp_ns, std::int64_t period_ns);

 private:
  struct Pose {
    double x = 0, y = 0, theta = 0;
  };
  std::map<std::uint32_t, Pose> robots_;
  std::unique_ptr<nlohmann::json> message_;  // the last message, one pose per robot of robots_ (or null)
  bool emitted_ = false;
  std::int64_t last_emitted_ns_ = 0;
};

}  // namespace robodds::foxglove
