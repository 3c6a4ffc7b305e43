#include "sim/evaluator/consistency.hpp"

#include <algorithm>
#include <cmath>

#include "common/angle.hpp"

namespace robodds::evaluator {

namespace {

/// e^T P^-1 e of the x-y block; infinite when the block is not positive definite and the error
/// is not zero (a claim of certainty the error contradicts), 0 for no error.
double mahalanobis_squared_xy(const EstimateError& e) {
  const double a = e.cov[0], b = e.cov[1], c = e.cov[3], d = e.cov[4];
  const double det = a * d - b * c;
  if (!(a > 0.0) || !(det > 0.0) || !std::isfinite(det)) {
    return e.ex == 0.0 && e.ey == 0.0 ? 0.0 : INFINITY;
  }
  // P^-1 = [d -b; -c a] / det
  return (d * e.ex * e.ex - (b + c) * e.ex * e.ey + a * e.ey * e.ey) / det;
}

void write_counts(JsonWriter& json, const ConsistencyStats& s) {
  json.value("samples", static_cast<std::int64_t>(s.samples));
  json.value("valid_samples", static_cast<std::int64_t>(s.valid_samples));
  json.value("overconfident_samples", static_cast<std::int64_t>(s.overconfident));
  json.value("overconfident_fraction", s.overconfident_fraction);
}

}  // namespace

bool overconfident(const EstimateError& e) {
  if (!e.valid) {
    return false;
  }
  if (mahalanobis_squared_xy(e) > kOutside3SigmaEllipse2d) {
    return true;
  }
  const double var_theta = e.cov[8];
  const double bound = var_theta > 0.0 && std::isfinite(var_theta) ? 3.0 * std::sqrt(var_theta) : 0.0;
  return std::abs(e.etheta) > bound;
}

bool overconfident_scalar(bool valid, double error, double variance) {
  if (!valid) {
    return false;
  }
  const double bound = variance > 0.0 && std::isfinite(variance) ? 3.0 * std::sqrt(variance) : 0.0;
  return std::abs(error) > bound;
}

void ConsistencyTracker::add(const EstimateError& e) {
  record(e.step, e.valid, overconfident(e), std::hypot(e.ex, e.ey), std::abs(e.etheta));
}

void ConsistencyTracker::add_scalar(std::uint64_t step, bool valid, double error, double variance) {
  record(step, valid, overconfident_scalar(valid, error, variance), std::abs(error), 0.0);
}

void ConsistencyTracker::record(std::uint64_t step, bool valid, bool over, double error, double heading_error) {
  ++stats_.samples;
  if (!valid) {
    in_run_ = false;
    return;
  }
  ++stats_.valid_samples;
  stats_.worst_position_error_valid_m = std::max(stats_.worst_position_error_valid_m, error);
  stats_.worst_heading_error_valid_rad = std::max(stats_.worst_heading_error_valid_rad, heading_error);
  if (!over) {
    in_run_ = false;
    return;
  }
  ++stats_.overconfident;
  if (!in_run_) {
    in_run_ = true;
    run_first_ = step;
  }
  // A run of samples from run_first_ to this one spans their steps plus this sample's own.
  const double run_s = static_cast<double>(step - run_first_ + 1) * step_s_;
  stats_.longest_overconfident_s = std::max(stats_.longest_overconfident_s, run_s);
}

ConsistencyStats ConsistencyTracker::stats() const {
  ConsistencyStats s = stats_;
  s.overconfident_fraction = s.valid_samples == 0 ? 0.0 : static_cast<double>(s.overconfident) / static_cast<double>(s.valid_samples);
  return s;
}

void write_consistency(JsonWriter& json, const ConsistencyStats& s) {
  write_counts(json, s);
  json.value("worst_position_error_valid_m", s.worst_position_error_valid_m);
  json.value("worst_heading_error_valid_deg", s.worst_heading_error_valid_rad * 180.0 / kPi);
  json.value("longest_overconfident_s", s.longest_overconfident_s);
}

void write_scalar_consistency(JsonWriter& json, const ConsistencyStats& s, const char* worst_key) {
  write_counts(json, s);
  json.value(worst_key, s.worst_position_error_valid_m);
  json.value("longest_overconfident_s", s.longest_overconfident_s);
}

ConsistencyStats pooled(const ConsistencyStats& a, const ConsistencyStats& b) {
  ConsistencyStats s;
  s.samples = a.samples + b.samples;
  s.valid_samples = a.valid_samples + b.valid_samples;
  s.overconfident = a.overconfident + b.overconfident;
  s.overconfident_fraction = s.valid_samples == 0 ? 0.0 : static_cast<double>(s.overconfident) / static_cast<double>(s.valid_samples);
  s.worst_position_error_valid_m = std::max(a.worst_position_error_valid_m, b.worst_position_error_valid_m);
  s.worst_heading_error_valid_rad = std::max(a.worst_heading_error_valid_rad, b.worst_heading_error_valid_rad);
  s.longest_overconfident_s = std::max(a.longest_overconfident_s, b.longest_overconfident_s);
  return s;
}

}  // namespace robodds::evaluator
