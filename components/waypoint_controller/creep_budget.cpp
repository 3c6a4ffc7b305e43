#include "components/waypoint_controller/creep_budget.hpp"

#include <cmath>

namespace robodds::waypoint_controller {

CreepVerdict CreepBudget::check(double time_s, bool mission_done) {
  if (mission_done) {
    return CreepVerdict::kMissionDone;
  }
  if (had_valid_) {
    const bool position_known = position_std_m_ >= 0.0 && position_std_m_ < limits_.relearn_max_position_std_m;
    if (limits_.max_relearns <= 0 || !position_known) {
      return CreepVerdict::kAfterValidEstimate;
    }
    if (relearns_ >= limits_.max_relearns) {
      return CreepVerdict::kRelearnsSpent;
    }
    // Valid before, invalid now with the position still known: creep to learn the heading again.
    ++relearns_;
    had_valid_ = false;
    started_ = false;
    distance_m_ = 0.0;
    extensions_ = 0;
  }
  if (!started_) {
    started_ = true;
    started_s_ = time_s;
    budget_start_std_rad_ = heading_std_rad_;
  }
  CreepVerdict verdict = CreepVerdict::kAllowed;
  if (distance_m_ >= limits_.max_distance_m) {
    verdict = CreepVerdict::kDistanceSpent;
  } else if (time_s - started_s_ > limits_.max_time_s) {
    verdict = CreepVerdict::kTimeSpent;
  }
  if (verdict != CreepVerdict::kAllowed && extensions_ < limits_.max_extensions && budget_start_std_rad_ > 0.0 &&
      heading_std_rad_ >= 0.0 && heading_std_rad_ <= (1.0 - limits_.min_progress) * budget_start_std_rad_) {
    // The estimator is still learning the heading from the creep: one more budget from here.
    ++extensions_;
    started_s_ = time_s;
    distance_m_ = 0.0;
    budget_start_std_rad_ = heading_std_rad_;
    verdict = CreepVerdict::kAllowed;
  }
  return verdict;
}

void CreepBudget::observe_heading_std(double std_rad) {
  if (std::isfinite(std_rad) && std_rad >= 0.0) {
    heading_std_rad_ = std_rad;
  }
}

void CreepBudget::observe_position_std(double std_m, bool inputs_stale) {
  position_std_m_ = !inputs_stale && std::isfinite(std_m) && std_m >= 0.0 ? std_m : -1.0;
}

bool CreepBudget::estimator_restarted() {
  if (restarts_granted_ >= limits_.max_restarts) {
    return false;
  }
  ++restarts_granted_;
  had_valid_ = false;
  started_ = false;
  distance_m_ = 0.0;
  extensions_ = 0;
  return true;
}

void CreepBudget::crept(double v_mps, double period_s) { distance_m_ += std::abs(v_mps) * period_s; }

const char* describe(CreepVerdict verdict) {
  switch (verdict) {
    case CreepVerdict::kAllowed:
      return "";
    case CreepVerdict::kAfterValidEstimate:
      return "the estimate was valid before and its position is not known to invalid_estimate_relearn_max_position_std_m "
             "(or relearning is off): no creeping (zero command)";
    case CreepVerdict::kRelearnsSpent:
      return "the estimate was valid before and invalid_estimate_creep_relearns are used up since the last way-point: "
             "no creeping (zero command)";
    case CreepVerdict::kMissionDone:
      return "the mission is done: no creeping";
    case CreepVerdict::kDistanceSpent:
      return "creeping reached invalid_estimate_creep_max_m without a valid estimate";
    case CreepVerdict::kTimeSpent:
      return "creeping reached invalid_estimate_creep_limit_s without a valid estimate";
  }
  return "";
}

}  // namespace robodds::waypoint_controller
