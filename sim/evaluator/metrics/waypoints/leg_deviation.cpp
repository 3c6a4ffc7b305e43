#include "sim/evaluator/metrics/waypoints/leg_deviation.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace robodds::evaluator {

void LegDeviation::set_mission(std::vector<std::array<double, 2>> waypoints) { mission_ = std::move(waypoints); }

void LegDeviation::add_status(std::uint64_t step, std::size_t target_index, bool done) {
  if (done_) {
    return;
  }
  // Truth up to the step before this status belongs to the previous one's leg.
  if (has_status_ && step > 0) {
    count_pending_through(step - 1);
  }
  has_status_ = true;
  status_step_ = step;
  target_index_ = target_index;
  if (done) {
    done_ = true;
    done_step_ = step;
    pending_.clear();
    return;
  }
  count_pending_through(status_step_);
}

void LegDeviation::add_truth(std::uint64_t step, double x_m, double y_m) {
  if (!has_start_) {
    start_ = {x_m, y_m};
    has_start_ = true;
  }
  if (done_ && step >= done_step_) {
    return;
  }
  pending_.push_back(Truth{step, x_m, y_m});
  if (pending_.size() > kMaxPending) {
    pending_.pop_front();
  }
  if (has_status_) {
    count_pending_through(status_step_);
  }
}

void LegDeviation::count_pending_through(std::uint64_t last_step) {
  while (!pending_.empty() && pending_.front().step <= last_step) {
    count(pending_.front(), target_index_);
    pending_.pop_front();
  }
}

void LegDeviation::count(const Truth& truth, std::size_t target_index) {
  if (target_index >= mission_.size() || !has_start_) {
    return;
  }
  const std::array<double, 2>& from = target_index == 0 ? start_ : mission_[target_index - 1];
  const std::array<double, 2>& to = mission_[target_index];
  const double dx = to[0] - from[0];
  const double dy = to[1] - from[1];
  const double length = std::hypot(dx, dy);
  if (!(length > kLegSettleM)) {
    return;  // a leg shorter than the settling distance has no straight part to judge
  }
  const double px = truth.x - from[0];
  const double py = truth.y - from[1];
  const double along = (dx * px + dy * py) / length;
  if (along <= kLegSettleM || along >= length) {
    return;
  }
  const double cross = (dx * py - dy * px) / length;
  ++samples_;
  sum_squares_ += cross * cross;
  max_abs_ = std::max(max_abs_, std::abs(cross));
}

std::optional<LegDeviationFigures> LegDeviation::figures() const {
  if (samples_ == 0) {
    return std::nullopt;
  }
  return LegDeviationFigures{samples_, std::sqrt(sum_squares_ / static_cast<double>(samples_)), max_abs_};
}

}  // namespace robodds::evaluator
