#include "common/sample_stats.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace robodds::stats {

double student_t_975(std::size_t dof) {
  static constexpr std::array<double, 30> kTable = {
      12.7062, 4.3027, 3.1824, 2.7764, 2.5706, 2.4469, 2.3646, 2.3060, 2.2622, 2.2281,
      2.2010,  2.1788, 2.1604, 2.1448, 2.1314, 2.1199, 2.1098, 2.1009, 2.0930, 2.0860,
      2.0796,  2.0739, 2.0687, 2.0639, 2.0595, 2.0555, 2.0518, 2.0484, 2.0452, 2.0423};
  if (dof == 0) {
    throw std::invalid_argument("student_t_975: dof must be >= 1");
  }
  if (dof <= kTable.size()) {
    return kTable[dof - 1];
  }
  const double z = 1.959963984540054;
  const double n = static_cast<double>(dof);
  const double z3 = z * z * z;
  const double z5 = z3 * z * z;
  const double z7 = z5 * z * z;
  return z + (z3 + z) / (4.0 * n) + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * n * n) +
         (3.0 * z7 + 19.0 * z5 + 17.0 * z3 - 15.0 * z) / (384.0 * n * n * n);
}

SampleSummary summarize(const std::vector<double>& values) {
  if (values.empty()) {
    throw std::invalid_argument("summarize: no values");
  }
  const double n = static_cast<double>(values.size());
  double sum = 0.0;
  for (double v : values) {
    sum += v;
  }
  SampleSummary result;
  result.count = values.size();
  result.mean = sum / n;
  const auto [min, max] = std::minmax_element(values.begin(), values.end());
  result.min = *min;
  result.max = *max;
  if (values.size() < 2) {
    return result;
  }
  double sum_sq = 0.0;
  for (double v : values) {
    sum_sq += (v - result.mean) * (v - result.mean);
  }
  result.stddev = std::sqrt(sum_sq / (n - 1.0));
  result.ci95 = student_t_975(values.size() - 1) * result.stddev / std::sqrt(n);
  return result;
}

}  // namespace robodds::stats
