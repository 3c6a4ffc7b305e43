#include "sim/evaluator/metrics/waypoints/waypoint_metrics.hpp"

#include <algorithm>
#include <cmath>

namespace robodds::evaluator {

void WaypointTracker::add_status(const StatusSample& s) {
  has_status_ = true;
  last_step_ = s.step;
  waypoints_reached_ = std::max(waypoints_reached_, s.waypoints_reached);
  epsilon_m_ = s.epsilon;
  if (s.switched) {
    switch_distance_estimate_m_.push_back(s.switch_distance);
    Switch sw;
    sw.step = s.step;
    sw.reached_index = s.waypoints_reached > 0 ? s.waypoints_reached - 1 : 0;
    switches_.push_back(sw);
  }
  if (s.done && !done_) {
    done_ = true;
    done_step_ = s.step;
  }
}

void WaypointTracker::match(const TruthWindow& truth) {
  for (; next_unmatched_ < switches_.size() && truth.reached(switches_[next_unmatched_].step); ++next_unmatched_) {
    Switch& sw = switches_[next_unmatched_];
    if (const PoseSample* t = truth.at(sw.step)) {
      sw.has_truth = true;
      sw.x = t->x;
      sw.y = t->y;
    }
  }
}

std::uint64_t WaypointTracker::needed_from() const {
  return next_unmatched_ < switches_.size() ? std::min(switches_[next_unmatched_].step, last_step_) : last_step_;
}

WaypointMetrics WaypointTracker::metrics(const PoseSample* final_truth, double step_s) const {
  WaypointMetrics m;
  m.waypoints_total = static_cast<std::uint32_t>(mission_.size());
  m.waypoints_reached = waypoints_reached_;
  m.epsilon_m = epsilon_m_;
  m.switch_distance_estimate_m = switch_distance_estimate_m_;
  for (const Switch& sw : switches_) {
    if (sw.has_truth && sw.reached_index < mission_.size()) {
      const auto& w = mission_[sw.reached_index];
      m.switch_distance_true_m.push_back(std::hypot(sw.x - w[0], sw.y - w[1]));
    }
  }
  if (done_) {
    m.time_to_final_s = static_cast<double>(done_step_) * step_s;
  }
  if (final_truth != nullptr && !mission_.empty()) {
    m.final_error_true_m = std::hypot(final_truth->x - mission_.back()[0], final_truth->y - mission_.back()[1]);
  }
  return m;
}

}  // namespace robodds::evaluator
