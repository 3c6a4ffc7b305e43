#pragma once
// summary.json's "standby", only when the scenario has a hot standby (ComponentSpec::standby_for)
// and estimate/pose is recorded: per robot the longest gap between estimate/pose samples after
// metrics_after_s, the hand-over time (handover.hpp), and its ends in s since the run's start.

#include <cstdint>
#include <vector>

#include "common/json_writer.hpp"
#include "sim/evaluator/handover.hpp"
#include "sim/evaluator/module/metrics_setup.hpp"
#include "sim/evaluator/module/per_robot.hpp"

namespace robodds::evaluator {

class StandbySummary {
 public:
  /// Watches estimate/pose when the scenario has a hot standby and the topic is recorded.
  void configure(MetricsSetup& setup);
  /// Before the first sample: gaps count from this stamp (s) on.
  void set_gaps_after_s(double after_s) { gaps_after_s_ = after_s; }
  /// The section for the robots `keys`, times from the run's start `start_s` (a stamp, s); none
  /// without a hot standby.
  void write(JsonWriter& json, const std::vector<std::uint64_t>& keys, double start_s) const;

 private:
  bool active_ = false;
  double gaps_after_s_ = 0.0;
  PerRobot<GapTracker> robots_;  // estimate/pose stamps (s)
};

}  // namespace robodds::evaluator
