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
  const auto to = std::upper_bound(sorted_.begin(), sorted_.end(), value);
  if (sorted_.size() < ring_.size()) {
    sorted_.insert(to, value);
  } else {
    // Full: the oldest value (at next_ in the ring) leaves and the new one takes its place; only
    // the values between the two positions move (a third of the window on average, not all of
    // it as an erase plus an insert would: ~3x cheaper at 256).
    const auto from = std::lower_bound(sorted_.begin(), sorted_.end(), ring_[next_]);
    if (to <= from) {
      std::move_backward(to, from, from + 1);  // the values in [to, from) are > value
      *to = value;
    } else {
      std::move(from + 1, to, from);  // the values in (from, to) are <= value
      *(to - 1) = value;
    }
  }
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
