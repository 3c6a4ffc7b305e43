#pragma once
// Issue 27: is an estimate as good as it says? For each estimate matched with truth at its step,
// the error (estimate - truth) is judged against the covariance the estimate reports: a valid
// estimate is over-confident when its position error lies outside the 3-sigma ellipse of its
// reported x-y covariance (Mahalanobis distance squared > 11.83, the chi-square quantile with 2
// degrees of freedom that a 1-D 3 sigma leaves outside: 0.27 %) or its heading error exceeds 3
// reported heading sigmas. A consistent estimator is over-confident in ~0.3-0.5 % of its valid
// samples; a reported covariance of zero with a nonzero error is over-confident always.
// Pure: steps are simulation steps, errors in m and rad, covariances in m^2, rad^2, m rad.
#include <array>
#include <cstddef>
#include <cstdint>

#include "common/json_writer.hpp"

namespace robodds::evaluator {

/// Mahalanobis distance squared beyond which a 2-D error is outside its 3-sigma ellipse:
/// chi-square(2 dof) at 1 - 0.0027 = -2 ln(0.0027).
inline constexpr double kOutside3SigmaEllipse2d = 11.829;

/// One estimate against truth: its error and what it reported.
struct EstimateError {
  std::uint64_t step = 0;
  bool valid = false;
  double ex = 0.0, ey = 0.0;  // m, estimate - truth (world, or the estimate's own frame)
  double etheta = 0.0;        // rad, wrapped to [-pi, pi)
  std::array<double, 9> cov{};  // row-major 3x3 covariance of (x, y, theta) as reported
};

struct ConsistencyStats {
  std::size_t samples = 0;        // matched with truth
  std::size_t valid_samples = 0;  // of those, said valid
  std::size_t overconfident = 0;  // valid and outside their reported 3 sigma
  double overconfident_fraction = 0.0;    // overconfident / valid_samples (0 without valid samples)
  double worst_position_error_valid_m = 0.0;
  double worst_heading_error_valid_rad = 0.0;
  double longest_overconfident_s = 0.0;  // longest run of consecutive over-confident valid samples
};

/// True when `e`, valid, lies outside the 3 sigma its covariance reports (position or heading).
bool overconfident(const EstimateError& e);
/// A scalar estimate (e.g. a range rate): true when valid and |error| > 3 sqrt(variance); a
/// variance of zero (or not finite) with a nonzero error always is.
bool overconfident_scalar(bool valid, double error, double variance);

/// Accumulates one stream of estimates (step order) of one robot or pair.
class ConsistencyTracker {
 public:
  /// `step_s`: s per step, for the run lengths.
  explicit ConsistencyTracker(double step_s) : step_s_(step_s) {}
  void add(const EstimateError& e);
  /// A scalar estimate at `step`: |error| goes into worst_position_error_valid_m (whatever its
  /// unit: write_scalar_consistency names it), the heading figures stay 0.
  void add_scalar(std::uint64_t step, bool valid, double error, double variance);
  ConsistencyStats stats() const;

 private:
  void record(std::uint64_t step, bool valid, bool over, double error, double heading_error);

  double step_s_;
  ConsistencyStats stats_;
  bool in_run_ = false;
  std::uint64_t run_first_ = 0;  // step of the run's first over-confident sample
};

/// Several trackers' figures as one (e.g. every robot of a stage): counts added, worst of the worst.
ConsistencyStats pooled(const ConsistencyStats& a, const ConsistencyStats& b);

/// Its keys in summary.json (into the object `json` is in): samples, valid_samples,
/// overconfident_samples, overconfident_fraction, worst_position_error_valid_m,
/// worst_heading_error_valid_deg, longest_overconfident_s.
void write_consistency(JsonWriter& json, const ConsistencyStats& s);
/// The same for a scalar estimate: samples, valid_samples, overconfident_samples,
/// overconfident_fraction, `worst_key` (the largest |error| while valid) and longest_overconfident_s.
void write_scalar_consistency(JsonWriter& json, const ConsistencyStats& s, const char* worst_key);

}  // namespace robodds::evaluator
