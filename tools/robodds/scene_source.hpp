#pragma once
// --foxglove-scene of `robodds record` and `robodds bridge`: the robots' poses come from
// plant/state (the plant's true states), decoded from the payloads the tools receive raw.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "runtime/topics/topic_catalog.hpp"
#include "system/foxglove/robot_poses.hpp"

namespace robodds {

using foxglove::kSceneSource;

/// The index of kSceneSource in `topics`; ConfigError when it is not there ("add it to `where`").
std::size_t require_scene_source(const std::vector<const TopicInfo*>& topics, const std::string& where);

/// The scene as the tools send or write it: every kSceneSource sample updates the robots' poses,
/// and a scene message is due at most once per foxglove::kScenePeriodNs of the samples' own stamps
/// (foxglove::RobotPoses::due), whatever the number of robots: 200 robots at 100 Hz give 20
/// messages per second of sample time, not 20,000 (each of 200 poses).
class SceneFeed {
 public:
  /// `tool` names the command in the one log line of a payload that does not decode.
  explicit SceneFeed(std::string tool);
  /// Takes one kSceneSource payload (XCDR1 with its encapsulation header) stamped `stamp_ns`: the
  /// foxglove.PosesInFrame JSON of every robot seen when a message is due, nullopt otherwise (and
  /// when the payload does not decode: logged once; the raw channel still carries every sample).
  std::optional<std::string> take(const std::uint8_t* data, std::size_t size, std::int64_t stamp_ns);

 private:
  std::string tool_;
  foxglove::RobotPoses poses_;
  bool error_logged_ = false;
};

}  // namespace robodds
