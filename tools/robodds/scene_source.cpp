#include "tools/robodds/scene_source.hpp"

#include <algorithm>
#include <memory>
#include <utility>

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

SceneFeed::SceneFeed(std::string tool) : tool_(std::move(tool)) {}

std::optional<std::string> SceneFeed::take(const std::uint8_t* data, std::size_t size, std::int64_t stamp_ns) {
  try {
    const std::shared_ptr<void> decoded = sample_codec().deserialize(idl::type_name<idl::RobotState>(), data, size);
    const auto& state = *static_cast<const idl::RobotState*>(decoded.get());
    poses_.update(state.robot_id(), state.x(), state.y(), state.theta());
  } catch (const ConfigError& e) {
    if (!error_logged_) {
      log::warn(tool_, std::string("--foxglove-scene: a ") + kSceneSource + " sample does not decode: " + e.what());
      error_logged_ = true;
    }
    return std::nullopt;
  }
  if (!poses_.due(stamp_ns, foxglove::kScenePeriodNs)) {
    return std::nullopt;
  }
  return poses_.json(stamp_ns);
}

}  // namespace robodds
