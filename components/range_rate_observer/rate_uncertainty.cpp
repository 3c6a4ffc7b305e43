#include "components/range_rate_observer/rate_uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/number_text.hpp"

namespace robodds::range_rate_observer {

namespace {
/// Fewer samples than this in the window: no line is fitted (a rate far below 10 Hz or a gap).
constexpr std::size_t kMinWindowSamples = 8;

}  // namespace

const params::ParamTable<RateUncertaintyParams>& rate_uncertainty_param_table() {
  using P = RateUncertaintyParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>("The reported std of the range-rate estimate (issue 27), measured against a least-squares slope.")
          .add("check_window_s", &P::check_window_s, "s", params::positive(),
               "span of the least-squares line through the ranges the estimate is checked against")
          .add("fast_tau_s", &P::fast_tau_s, "s", params::positive(), "time constant of the quickly following mean of the squared differences")
          .add("slow_tau_s", &P::slow_tau_s, "s", params::positive(), "time constant of the slowly forgetting mean of the squared differences")
          .add("initial_rate_std_mps", &P::initial_rate_std_mps, "m/s", params::non_negative("0 = the robot's max_speed_mps / 3; 5 without one"),
               "std of the true range rate at the first sample (the observer starts at 0 m/s)")
          .add("min_std_mps", &P::min_std_mps, "m/s", params::non_negative(),
               "the smallest std reported (the evaluation's own resolution of a noise-free rate)");
  return table;
}

void RateUncertaintyParams::validate() const {
  rate_uncertainty_param_table().check_ranges(*this);
  if (!(initial_rate_std_mps > 0.0)) {  // the node's 0 (the robot's top speed / 3) is resolved before
    throw std::invalid_argument("initial_rate_std_mps: must be > 0 m/s (got " + shortest_text(initial_rate_std_mps) + ")");
  }
  if (!(range_accel_mps2 >= 0.0) || !std::isfinite(range_accel_mps2)) {
    throw std::invalid_argument("range_accel_mps2: must be >= 0 m/s^2 (got " + shortest_text(range_accel_mps2) + ")");
  }
}

RateUncertainty::RateUncertainty(RateUncertaintyParams params) : params_(params) { params_.validate(); }

void RateUncertainty::restart(double start_std_mps) {
  window_.clear();
  const double var = start_std_mps * start_std_mps;
  fast_var_ = std::max(var, 0.0);
  slow_var_ = fast_var_;
  checks_ = 0;
}

void RateUncertainty::add(double time_s, double range_m, double v_hat_mps) {
  window_.push_back({time_s, range_m, v_hat_mps});
  while (window_.size() > 1 && window_.front().t < time_s - params_.check_window_s - 1e-9) {
    window_.pop_front();
  }
  // 1e-9 s: a window of 2 s at 50 Hz spans exactly 2 s whatever the rounding.
  if (window_.size() < kMinWindowSamples || time_s - window_.front().t < params_.check_window_s - 1e-9) {
    return;
  }
  const double n = static_cast<double>(window_.size());
  const double t0 = window_.front().t;
  const double r0 = window_.front().r;
  double st = 0.0, sr = 0.0;
  for (const Sample& s : window_) {
    st += s.t - t0;
    sr += s.r - r0;
  }
  const double t_mean = st / n;
  const double r_mean = sr / n;
  double stt = 0.0, str = 0.0;
  for (const Sample& s : window_) {
    const double dt = s.t - t0 - t_mean;
    stt += dt * dt;
    str += dt * (s.r - r0 - r_mean);
  }
  if (!(stt > 0.0)) {
    return;
  }
  const double slope_mps = str / stt;
  const double d = estimate_at(t0 + t_mean) - slope_mps;
  // The first check after a (re)start weighs like one mean sample period.
  const double since_s = checks_ == 0 ? (window_.back().t - window_.front().t) / (n - 1.0) : time_s - last_check_s_;
  const double fast_keep = std::exp(-since_s / params_.fast_tau_s);
  const double slow_keep = std::exp(-since_s / params_.slow_tau_s);
  fast_var_ = fast_keep * fast_var_ + (1.0 - fast_keep) * d * d;
  slow_var_ = slow_keep * slow_var_ + (1.0 - slow_keep) * d * d;
  last_check_s_ = time_s;
  ++checks_;
}

double RateUncertainty::std_mps() const {
  return std::max(std::sqrt(std::max(fast_var_, slow_var_)), params_.min_std_mps);
}

double RateUncertainty::estimate_at(double t) const {
  const auto after = std::lower_bound(window_.begin(), window_.end(), t, [](const Sample& s, double time) { return s.t < time; });
  if (after == window_.begin()) {
    return after->v;
  }
  if (after == window_.end()) {
    return window_.back().v;
  }
  const Sample& a = *(after - 1);
  const Sample& b = *after;
  const double w = (t - a.t) / (b.t - a.t);
  return a.v + w * (b.v - a.v);
}

}  // namespace robodds::range_rate_observer
