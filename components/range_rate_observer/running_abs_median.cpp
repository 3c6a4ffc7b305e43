#include "components/range_rate_observer/running_abs_median.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/number_text.hpp"

namespace robodds::range_rate_observer {

namespace {
/// 1 / Phi^-1(3/4): the sigma of a zero-mean Gaussian whose median |x| is 1.
constexpr double kMedianAbsToSigma = 1.482602218505602;
}  // namespace

RunningAbsMedian::RunningAbsMedian(std::size_t window) {
  if (window == 0) {
    throw std::invalid_argument("running median: window must be at least 1 value");
  }
  ring_.assign(window, 0.0);
  sorted_.reserve(window);
}

void RunningAbsMedian::add(double x) {
  if (!std::isfinite(x)) {
    throw std::invalid_argument("running median: non-finite value " + shortest_text(x));
  }
  const double value = std::abs(x);
  if (sorted_.size() == ring_.size()) {
    // Full: the oldest value leaves; it is the one at next_ in the ring.
    sorted_.erase(std::lower_bound(sorted_.begin(), sorted_.end(), ring_[next_]));
  }
  sorted_.insert(std::upper_bound(sorted_.begin(), sorted_.end(), value), value);
  ring_[next_] = value;
  next_ = (next_ + 1) % ring_.size();
}

double RunningAbsMedian::median_abs() const {
  if (sorted_.empty()) {
    return 0.0;
  }
  return sorted_[(sorted_.size() - 1) / 2];
}

double RunningAbsMedian::sigma() const { return kMedianAbsToSigma * median_abs(); }

}  // namespace robodds::range_rate_observer
