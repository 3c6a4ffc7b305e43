#pragma once
// Time series the evaluator keeps per robot, and the error statistics computed from them.
// Pure: steps are simulation steps, positions in m (world), headings in rad.

#include <cstdint>
#include <vector>

namespace robodds::evaluator {

struct PoseSample {
  std::uint64_t step = 0;
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
};

using Track = std::vector<PoseSample>;  // in step order

/// Sum of the distances between consecutive samples, m.
double path_length(const Track& track);

struct ErrorStats {
  double rmse = 0.0;       // m, root mean square position error
  double max_abs = 0.0;    // m
  std::size_t count = 0;   // samples matched with truth at the same step
};

/// RMSE over several ErrorStats (e.g. all robots), each weighted by its sample count.
class PooledRmse {
 public:
  void add(const ErrorStats& stats) {
    sum_squares_ += stats.rmse * stats.rmse * static_cast<double>(stats.count);
    count_ += stats.count;
  }
  bool empty() const { return count_ == 0; }
  double rmse() const;

 private:
  double sum_squares_ = 0.0;
  std::size_t count_ = 0;
};

/// Position error of `estimate` against `truth` at equal steps, for steps >= from_step.
ErrorStats position_error(const Track& truth, const Track& estimate, std::uint64_t from_step);

/// Heading error (wrapped) in rad, same matching.
ErrorStats heading_error(const Track& truth, const Track& estimate, std::uint64_t from_step);

}  // namespace robodds::evaluator
