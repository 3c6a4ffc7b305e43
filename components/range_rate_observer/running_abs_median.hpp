#pragma once
// A robust online spread: the median of |x| over the last `window` values. A minority of
// outliers (fewer than half the window: the range jumps a restart rule must detect, a lost or
// wild sample) cannot move it, unlike a mean or an unclipped EWMA of x^2. For zero-mean Gaussian
// x, median |x| = 0.6745 sigma, so sigma() = 1.4826 median |x| (the MAD scale).

#include <cstddef>
#include <vector>

namespace robodds::range_rate_observer {

class RunningAbsMedian {
 public:
  /// Throws std::invalid_argument for a window of 0.
  explicit RunningAbsMedian(std::size_t window);

  /// Adds |x|, forgetting the oldest value once `window` are held. A non-finite x throws
  /// std::invalid_argument and changes nothing. O(window) memmove at worst, no allocation after
  /// the window is full.
  void add(double x);
  /// How many values are held (at most window).
  std::size_t count() const { return sorted_.size(); }
  std::size_t window() const { return ring_.size(); }
  /// The median of the |x| held (the lower middle one for an even count); 0 when empty.
  double median_abs() const;
  /// The standard deviation of zero-mean Gaussian x with that median |x|: 1.4826 median_abs().
  double sigma() const;

 private:
  std::vector<double> ring_;    // the last `window` |x| in arrival order (ring buffer)
  std::size_t next_ = 0;        // where the next |x| goes in ring_
  std::vector<double> sorted_;  // the same values, sorted ascending
};

}  // namespace robodds::range_rate_observer
