#pragma once
// --foxglove-scene of `robodds record` and `robodds bridge`: the robots' poses come from
// plant/state (the plant's true states), decoded from the payloads the tools receive raw.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "runtime/topics/topic_catalog.hpp"
#include "system/foxglove/robot_poses.hpp"

namespace robodds {

using foxglove::kSceneSource;

/// The index of kSceneSource in `topics`; ConfigError when it is not there ("add it to `where`").
std::size_t require_scene_source(const std::vector<const TopicInfo*>& topics, const std::string& where);

/// Decodes one kSceneSource payload (XCDR1 with its encapsulation header) into `poses`. False
/// when it does not decode: `tool` logs that once (its raw channel still carries every sample).
bool update_poses(foxglove::RobotPoses& poses, const std::uint8_t* data, std::size_t size, const std::string& tool,
                  bool& error_logged);

}  // namespace robodds
