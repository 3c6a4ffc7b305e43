#include "sim/evaluator/waypoint_metrics.hpp"

#include <algorithm>
#include <cmath>

namespace robodds::evaluator {
namespace {

const PoseSample* truth_at(const Track& truth, std::uint64_t step) {
  auto it = std::lower_bound(truth.begin(), truth.end(), step, [](const PoseSample& s, std::uint64_t v) { return s.step < v; });
  return it != truth.end() && it->step == step ? &*it : nullptr;
}

}  // namespace

WaypointMetrics waypoint_metrics(const Track& truth, const std::vector<StatusSample>& status,
                                 const std::vector<std::array<double, 2>>& mission, double step_s) {
  WaypointMetrics m;
  m.waypoints_total = static_cast<std::uint32_t>(mission.size());
  for (const StatusSample& s : status) {
    m.waypoints_reached = std::max(m.waypoints_reached, s.waypoints_reached);
    m.epsilon_m = s.epsilon;
    if (s.switched) {
      m.switch_distance_estimate_m.push_back(s.switch_distance);
      const std::size_t reached_index = s.waypoints_reached > 0 ? s.waypoints_reached - 1 : 0;
      const PoseSample* t = truth_at(truth, s.step);
      if (t != nullptr && reached_index < mission.size()) {
        m.switch_distance_true_m.push_back(std::hypot(t->x - mission[reached_index][0], t->y - mission[reached_index][1]));
      }
    }
    if (s.done && m.time_to_final_s < 0.0) {
      m.time_to_final_s = static_cast<double>(s.step) * step_s;
    }
  }
  if (!truth.empty() && !mission.empty()) {
    m.final_error_true_m = std::hypot(truth.back().x - mission.back()[0], truth.back().y - mission.back()[1]);
  }
  return m;
}

}  // namespace robodds::evaluator
