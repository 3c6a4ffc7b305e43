#pragma once
// Hand-over time of a hot standby (docs/architecture.md, "One producer per instance and hot
// standby"): the longest silence in a topic's samples, e.g. estimate/pose between the last
// sample of the dead primary and the first of its standby. Pure and incremental (one sample at
// a time, constant memory): the evaluator feeds it every robot's estimate/pose stamps and writes
// the longest gap to summary.json's "standby" section when the scenario has a hot standby.

#include <cstdint>

namespace robodds::evaluator {

struct Gap {
  double length_s = 0.0;  // s between the two samples
  double from_s = 0.0;    // stamp of the last sample before the gap
  double to_s = 0.0;      // stamp of the first sample after it
};

class GapTracker {
 public:
  /// Samples stamped before after_s (start-up, discovery) are not counted.
  explicit GapTracker(double after_s = 0.0) : after_s_(after_s) {}
  /// A sample stamped t_s (s). A stamp older than the newest seen (a reordered sample) is ignored.
  void observe(double t_s);
  /// The longest gap so far (all zero before two samples).
  const Gap& longest() const { return longest_; }
  std::uint64_t samples() const { return samples_; }

 private:
  double after_s_;
  double last_s_ = 0.0;
  std::uint64_t samples_ = 0;
  Gap longest_;
};

}  // namespace robodds::evaluator
