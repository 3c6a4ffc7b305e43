#pragma once
// Online estimate of the position fixes' noise from the filter's own innovations (issue 27,
// finding 2): a real sensor is never exactly as configured, and a filter that assumes fixes 3x
// less noisy than they are takes correct fixes for outliers and keeps redrawing its cloud.
//
// Per fix, the innovation e = z - m has covariance P + sigma^2 I (P: the cloud's x-y covariance,
// sigma^2: the fix variance per axis), so e^T e / (sigma^2 + p) is chi-square(2) with median
// 2 ln 2 (p = trace(P) / 2). Each fix gives the sample e^T e / (2 ln 2) - p, whose median over the
// last `window_fixes` fixes is sigma^2. The median, not the mean: gross outliers (up to nearly half
// the fixes) and the few large innovations of a lagging cloud hardly move it. The estimate never
// goes below the configured variance (the floor): the configuration is the sensor's best case, and
// a smaller value would make the filter trust lucky streaks.

#include <cstddef>
#include <vector>

namespace robodds::pf_estimator {

class FixNoiseEstimator {
 public:
  /// floor_std_m > 0 (m, per axis); window_fixes = 0 turns estimation off (always the floor).
  FixNoiseEstimator(double floor_std_m, std::size_t window_fixes);

  /// One fix: innovation (ex_m, ey_m) against the cloud mean and the cloud's variance per axis
  /// cloud_variance_m2 = trace(P) / 2 (m^2).
  void add(double ex_m, double ey_m, double cloud_variance_m2);

  /// The fix std per axis (m) to use: the floor until `min_fixes` samples, then
  /// sqrt(max(floor^2, running median)).
  double std_m() const { return std_m_; }
  double variance_m2() const { return std_m_ * std_m_; }
  std::size_t samples() const { return count_ < samples_.size() ? count_ : samples_.size(); }

  /// Samples needed before the estimate leaves the floor (a median of fewer is too noisy).
  static constexpr std::size_t kMinFixes = 20;

 private:
  double floor_variance_m2_;
  double std_m_;
  std::vector<double> samples_;  // ring buffer, m^2
  std::vector<double> scratch_;  // for nth_element; reused, no allocation per fix
  std::size_t count_ = 0;
};

}  // namespace robodds::pf_estimator
