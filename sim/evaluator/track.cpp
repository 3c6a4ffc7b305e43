#include "sim/evaluator/track.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "common/angle.hpp"

namespace robodds::evaluator {
namespace {

ErrorStats matched_error(const Track& truth, const Track& estimate, std::uint64_t from_step,
                         const std::function<double(const PoseSample&, const PoseSample&)>& error) {
  ErrorStats stats;
  double sum_sq = 0.0;
  auto t = truth.begin();
  for (const PoseSample& e : estimate) {
    if (e.step < from_step) {
      continue;
    }
    t = std::lower_bound(t, truth.end(), e.step, [](const PoseSample& s, std::uint64_t step) { return s.step < step; });
    if (t == truth.end()) {
      break;
    }
    if (t->step != e.step) {
      continue;
    }
    const double err = error(*t, e);
    sum_sq += err * err;
    stats.max_abs = std::max(stats.max_abs, std::abs(err));
    ++stats.count;
  }
  stats.rmse = stats.count > 0 ? std::sqrt(sum_sq / static_cast<double>(stats.count)) : 0.0;
  return stats;
}

}  // namespace

double path_length(const Track& track) {
  double length = 0.0;
  for (std::size_t i = 1; i < track.size(); ++i) {
    length += std::hypot(track[i].x - track[i - 1].x, track[i].y - track[i - 1].y);
  }
  return length;
}

double PooledRmse::rmse() const { return std::sqrt(sum_squares_ / static_cast<double>(count_)); }

ErrorStats position_error(const Track& truth, const Track& estimate, std::uint64_t from_step) {
  return matched_error(truth, estimate, from_step,
                       [](const PoseSample& t, const PoseSample& e) { return std::hypot(e.x - t.x, e.y - t.y); });
}

ErrorStats heading_error(const Track& truth, const Track& estimate, std::uint64_t from_step) {
  return matched_error(truth, estimate, from_step,
                       [](const PoseSample& t, const PoseSample& e) { return wrap_angle(e.theta - t.theta); });
}

}  // namespace robodds::evaluator
