#pragma once
// The median of a few values (the tracker's running cost median, the range noise level's running
// median of residual stds).

#include <algorithm>
#include <cstddef>
#include <vector>

namespace robodds::uwb_relative_estimator {

/// Median of `values` (the mean of the two middle ones for an even count); `values` not empty.
inline double median(std::vector<double> values) {
  const std::size_t n = values.size();
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(values.begin(), middle, values.end());
  const double upper = *middle;
  if (n % 2 == 1) {
    return upper;
  }
  return 0.5 * (upper + *std::max_element(values.begin(), middle));
}

}  // namespace robodds::uwb_relative_estimator
