#pragma once
// Mean and 95 % confidence interval of a sample of independent runs (Student's t), for the
// observer study. Pure, std only.

#include <cstddef>
#include <vector>

namespace robodds::range_rate::study {

struct MeanCi {
  double mean = 0.0;
  /// Half width of the two-sided 95 % confidence interval of the mean: t(0.975, n - 1) s / sqrt(n).
  /// 0 for a single value.
  double ci95 = 0.0;
};

/// The 0.975 quantile of Student's t with `dof` degrees of freedom (>= 1): exact table to 30,
/// then the Cornish-Fisher expansion (error < 1e-4).
double student_t_975(std::size_t dof);

/// Throws std::invalid_argument for an empty sample.
MeanCi mean_ci95(const std::vector<double>& values);

}  // namespace robodds::range_rate::study
