#pragma once
// What the evaluator keeps of each robot's time series while the run goes on, and the error
// statistics it computes from them incrementally: memory does not grow with the duration.
// Pure: steps are simulation steps, positions in m (world), headings in rad.

#include <cstddef>
#include <cstdint>
#include <deque>

namespace robodds::evaluator {

struct PoseSample {
  std::uint64_t step = 0;
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
};

/// A track reduced to what the summary needs: sample count, last sample and path length.
class TrackSummary {
 public:
  /// `sample` follows the previous one (step order).
  void add(const PoseSample& sample);
  bool empty() const { return count_ == 0; }
  std::size_t count() const { return count_; }
  const PoseSample& last() const { return last_; }  // valid unless empty()
  /// Sum of the distances between consecutive samples, m.
  double path_length() const { return length_; }

 private:
  std::size_t count_ = 0;
  PoseSample last_;
  double length_ = 0.0;
};

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

/// The recent truth samples of one robot (step order), kept while an estimate of their step may
/// still arrive: the owner drops what no consumer needs any more (drop_before), and the oldest
/// go beyond `capacity` samples, so an estimate that lags truth by more is not matched.
class TruthWindow {
 public:
  static constexpr std::size_t kDefaultCapacity = 4096;
  explicit TruthWindow(std::size_t capacity = kDefaultCapacity) : capacity_(capacity) {}
  void add(const PoseSample& sample);
  /// The first kept sample at `step`, nullptr if there is none.
  const PoseSample* at(std::uint64_t step) const;
  /// Truth has arrived up to `step` (a later sample at that step is never used).
  bool reached(std::uint64_t step) const { return any_ && last_step_ >= step; }
  void drop_before(std::uint64_t step);
  std::size_t size() const { return samples_.size(); }

 private:
  std::size_t capacity_;
  std::deque<PoseSample> samples_;
  std::uint64_t last_step_ = 0;
  bool any_ = false;
};

/// Error of a stream of estimates (in step order) against truth at equal steps, for steps >=
/// from_step, accumulated as the samples arrive: an estimate waits until truth has reached its
/// step, then counts if truth has a sample at that step. The same figures as matching whole
/// recorded tracks, as long as the estimates lag truth by less than the window holds.
class MatchedError {
 public:
  /// Error of `estimate` against `truth` (signed or not; squared and |.| are taken).
  using ErrorFn = double (*)(const PoseSample& truth, const PoseSample& estimate);
  MatchedError(ErrorFn error, std::uint64_t from_step) : error_(error), from_step_(from_step) {}

  void add(const PoseSample& estimate);
  /// Matches the waiting estimates that `truth` has reached, in arrival order.
  void match(const TruthWindow& truth);
  /// Estimates seen (matched or not, before from_step or not).
  bool seen() const { return seen_; }
  /// Truth before this step is of no more use to this stream.
  std::uint64_t needed_from() const;
  std::size_t waiting() const { return pending_.size(); }
  ErrorStats stats() const;

 private:
  ErrorFn error_;
  std::uint64_t from_step_;
  std::deque<PoseSample> pending_;
  std::uint64_t floor_ = 0;  // step of the last estimate matched or missed; earlier ones never match
  bool seen_ = false;
  double sum_squares_ = 0.0;
  double max_abs_ = 0.0;
  std::size_t count_ = 0;
};

/// Euclidean distance between the positions, m.
double position_distance(const PoseSample& truth, const PoseSample& estimate);
/// Heading difference (estimate - truth) wrapped to [-pi, pi), rad.
double heading_difference(const PoseSample& truth, const PoseSample& estimate);

}  // namespace robodds::evaluator
