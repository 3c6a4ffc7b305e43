#include "common/estimate_age.hpp"

#include <cmath>
#include <limits>

namespace robodds::control {

EstimateAge classify_estimate_age(double age_s, double producer_period_s, double timeout_s) {
  if (!(age_s <= timeout_s)) {
    return EstimateAge::kStale;  // NaN included
  }
  const double late_after_s = std::isfinite(producer_period_s) && producer_period_s > 0.0 ? 2.0 * producer_period_s : 0.0;
  return age_s <= late_after_s ? EstimateAge::kFresh : EstimateAge::kLate;
}

double producer_period_s(std::uint64_t step, std::uint64_t next_step, double step_s) {
  if (next_step <= step || next_step == std::numeric_limits<std::uint64_t>::max()) {
    return 0.0;
  }
  return static_cast<double>(next_step - step) * step_s;
}

}  // namespace robodds::control
