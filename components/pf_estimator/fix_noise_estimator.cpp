#include "components/pf_estimator/fix_noise_estimator.hpp"

#include <algorithm>
#include <cmath>

namespace robodds::pf_estimator {

FixNoiseEstimator::FixNoiseEstimator(double floor_std_m, std::size_t window_fixes)
    : floor_variance_m2_(floor_std_m * floor_std_m), std_m_(floor_std_m), samples_(window_fixes, 0.0),
      scratch_(window_fixes, 0.0) {}

void FixNoiseEstimator::add(double ex_m, double ey_m, double cloud_variance_m2) {
  if (samples_.empty()) {
    return;
  }
  // e^T e / (2 ln 2): its median is sigma^2 + p (chi-square(2) has median 2 ln 2).
  const double sample = (ex_m * ex_m + ey_m * ey_m) / (2.0 * std::log(2.0)) - cloud_variance_m2;
  samples_[count_ % samples_.size()] = sample;
  ++count_;
  const std::size_t n = samples();
  if (n < kMinFixes) {
    return;
  }
  std::copy(samples_.begin(), samples_.begin() + static_cast<std::ptrdiff_t>(n), scratch_.begin());
  const auto middle = scratch_.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(scratch_.begin(), middle, scratch_.begin() + static_cast<std::ptrdiff_t>(n));
  std_m_ = std::sqrt(std::max(floor_variance_m2_, *middle));
}

}  // namespace robodds::pf_estimator
