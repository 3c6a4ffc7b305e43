#pragma once
// Summary statistics of a sample of independent runs (seeds of a study or a sweep): mean, sample
// standard deviation, extremes and the 95 % confidence interval of the mean (Student's t).
// Pure, std only.

#include <cstddef>
#include <vector>

namespace robodds::stats {

struct SampleSummary {
  std::size_t count = 0;
  double mean = 0.0;
  /// Sample standard deviation (n - 1 in the denominator); 0 for a single value.
  double stddev = 0.0;
  double min = 0.0;
  double max = 0.0;
  /// Half width of the two-sided 95 % confidence interval of the mean: t(0.975, n - 1) s / sqrt(n).
  /// 0 for a single value.
  double ci95 = 0.0;
};

/// The 0.975 quantile of Student's t with `dof` degrees of freedom (>= 1): exact table to 30,
/// then the Cornish-Fisher expansion (error < 1e-4).
double student_t_975(std::size_t dof);

/// Throws std::invalid_argument for an empty sample.
SampleSummary summarize(const std::vector<double>& values);

}  // namespace robodds::stats
