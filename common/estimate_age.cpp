#include "common/estimate_age.hpp"

#include <cmath>
#include <limits>

#include "common/number_text.hpp"

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

bool LateEstimateWatch::late(double age_s, std::uint64_t step, std::uint64_t next_step, double step_s, double timeout_s,
                             std::string& first_warning) {
  const double period_s = producer_period_s(step, next_step, step_s);
  if (classify_estimate_age(age_s, period_s, timeout_s) != EstimateAge::kLate) {
    return false;
  }
  if (!told_) {
    told_ = true;
    first_warning = shortest_text(age_s) + " s old (> 2 periods of " + shortest_text(period_s) +
                    " s): holding the last command until it is fresh or stale (not logged again)";
  }
  return true;
}

}  // namespace robodds::control
