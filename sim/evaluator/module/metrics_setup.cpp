#include "sim/evaluator/module/metrics_setup.hpp"

#include <algorithm>

namespace robodds::evaluator {

bool MetricsSetup::recorded(const std::string& topic) const {
  return std::find(topics_.begin(), topics_.end(), topic) != topics_.end();
}

std::vector<std::uint32_t> MetricsSetup::scenario_robots() const {
  std::vector<std::uint32_t> ids;
  for (const RobotSpec& robot : ctx_.scenario().robots) {
    ids.push_back(robot.id);
  }
  return ids;
}

void MetricsSetup::record_own(const std::string& topic, RecorderFactory make) {
  if (!own_recorders_.emplace(topic, std::move(make)).second) {
    throw std::logic_error("evaluator: two metrics modules record '" + topic + "' themselves");
  }
}

const MetricsSetup::RecorderFactory* MetricsSetup::own_recorder(const std::string& topic) const {
  const auto it = own_recorders_.find(topic);
  return it != own_recorders_.end() ? &it->second : nullptr;
}

}  // namespace robodds::evaluator
