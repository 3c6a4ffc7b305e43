#include "tools/robodds/scene_source.hpp"

#include <algorithm>
#include <memory>

#include "idl/idl_schema.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/base/log.hpp"
#include "runtime/bus/sample_codec.hpp"

namespace robodds {

std::size_t require_scene_source(const std::vector<const TopicInfo*>& topics, const std::string& where) {
  const auto found = std::find_if(topics.begin(), topics.end(), [](const TopicInfo* t) { return t->name == kSceneSource; });
  if (found == topics.end()) {
    throw ConfigError(std::string("--foxglove-scene draws the robots from ") + kSceneSource + ": add it to " + where);
  }
  return static_cast<std::size_t>(found - topics.begin());
}

bool update_poses(foxglove::RobotPoses& poses, const std::uint8_t* data, std::size_t size, const std::string& tool,
                  bool& error_logged) {
  try {
    const std::shared_ptr<void> decoded = sample_codec().deserialize(idl::type_name<idl::RobotState>(), data, size);
    const auto& state = *static_cast<const idl::RobotState*>(decoded.get());
    poses.update(state.robot_id(), state.x(), state.y(), state.theta());
    return true;
  } catch (const ConfigError& e) {
    if (!error_logged) {
      log::warn(tool, std::string("--foxglove-scene: a ") + kSceneSource + " sample does not decode: " + e.what());
      error_logged = true;
    }
    return false;
  }
}

}  // namespace robodds
