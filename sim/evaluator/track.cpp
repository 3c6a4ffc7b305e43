#include "sim/evaluator/track.hpp"

#include <algorithm>
#include <cmath>

#include "common/angle.hpp"

namespace robodds::evaluator {

void TrackSummary::add(const PoseSample& sample) {
  if (count_ > 0) {
    length_ += std::hypot(sample.x - last_.x, sample.y - last_.y);
  }
  last_ = sample;
  ++count_;
}

double PooledRmse::rmse() const { return std::sqrt(sum_squares_ / static_cast<double>(count_)); }

void TruthWindow::add(const PoseSample& sample) {
  samples_.push_back(sample);
  if (samples_.size() > capacity_) {
    samples_.pop_front();
  }
  last_step_ = any_ ? std::max(last_step_, sample.step) : sample.step;
  any_ = true;
}

const PoseSample* TruthWindow::at(std::uint64_t step) const {
  auto it = std::lower_bound(samples_.begin(), samples_.end(), step,
                             [](const PoseSample& s, std::uint64_t v) { return s.step < v; });
  return it != samples_.end() && it->step == step ? &*it : nullptr;
}

void TruthWindow::drop_before(std::uint64_t step) {
  while (!samples_.empty() && samples_.front().step < step) {
    samples_.pop_front();
  }
}

void MatchedError::add(const PoseSample& estimate) {
  seen_ = true;
  if (estimate.step >= from_step_) {
    pending_.push_back(estimate);
  }
}

void MatchedError::match(const TruthWindow& truth) {
  while (!pending_.empty()) {
    const PoseSample& e = pending_.front();
    if (e.step >= floor_) {
      if (!truth.reached(e.step)) {
        return;  // its truth may still come
      }
      floor_ = e.step;
      if (const PoseSample* t = truth.at(e.step)) {
        const double err = error_(*t, e);
        sum_squares_ += err * err;
        max_abs_ = std::max(max_abs_, std::abs(err));
        ++count_;
      }
    }
    pending_.pop_front();
  }
}

std::uint64_t MatchedError::needed_from() const { return std::max(from_step_, floor_); }

ErrorStats MatchedError::stats() const {
  ErrorStats stats;
  stats.max_abs = max_abs_;
  stats.count = count_;
  stats.rmse = count_ > 0 ? std::sqrt(sum_squares_ / static_cast<double>(count_)) : 0.0;
  return stats;
}

double position_distance(const PoseSample& truth, const PoseSample& estimate) {
  return std::hypot(estimate.x - truth.x, estimate.y - truth.y);
}

double heading_difference(const PoseSample& truth, const PoseSample& estimate) {
  return wrap_angle(estimate.theta - truth.theta);
}

}  // namespace robodds::evaluator
