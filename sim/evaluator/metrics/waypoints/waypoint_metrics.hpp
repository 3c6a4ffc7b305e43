#pragma once
// Paper-1 way-point metrics from the controller status, truth and mission, accumulated as the
// samples arrive. Pure: steps are simulation steps; distances in m; times in s.

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "sim/evaluator/track.hpp"

namespace robodds::evaluator {

struct StatusSample {
  std::uint64_t step = 0;
  std::uint32_t waypoints_reached = 0;
  std::uint32_t waypoints_total = 0;
  bool done = false;
  bool switched = false;
  double switch_distance = 0.0;  // m, the controller's (estimated) distance at the switch
  double epsilon = 0.0;          // m
};

struct WaypointMetrics {
  std::uint32_t waypoints_reached = 0;
  std::uint32_t waypoints_total = 0;
  double time_to_final_s = -1.0;              // -1: the last way-point was never reached
  std::vector<double> switch_distance_estimate_m;
  std::vector<double> switch_distance_true_m;  // true distance to the reached way-point at the switch
  double final_error_true_m = 0.0;            // true distance to the last way-point at the end
  double epsilon_m = 0.0;
};

using Mission = std::vector<std::array<double, 2>>;  // the way-points [x, y] in order

/// One robot's way-point figures. Keeps one entry per switch (bounded by the mission, not by
/// the duration); a switch waits for the truth sample of its step like an estimate does.
class WaypointTracker {
 public:
  /// Status samples in step order.
  void add_status(const StatusSample& status);
  /// The mission in force; the latest one is the one measured against.
  void set_mission(Mission mission) { mission_ = std::move(mission); has_mission_ = true; }
  /// Looks up truth for the switches that `truth` has reached.
  void match(const TruthWindow& truth);
  bool has_status() const { return has_status_; }
  bool has_mission() const { return has_mission_; }
  /// Truth before this step is of no more use to the tracker.
  std::uint64_t needed_from() const;
  /// The figures so far; `final_truth` is the robot's last truth sample (nullptr: none).
  WaypointMetrics metrics(const PoseSample* final_truth, double step_s) const;

 private:
  struct Switch {
    std::uint64_t step = 0;
    std::size_t reached_index = 0;  // the way-point reached
    bool has_truth = false;
    double x = 0.0;  // m, true position at the switch
    double y = 0.0;
  };
  bool has_status_ = false;
  bool has_mission_ = false;
  Mission mission_;
  std::uint32_t waypoints_reached_ = 0;
  double epsilon_m_ = 0.0;
  bool done_ = false;
  std::uint64_t done_step_ = 0;  // the first status that said done
  std::uint64_t last_step_ = 0;
  std::vector<double> switch_distance_estimate_m_;
  std::vector<Switch> switches_;
  std::size_t next_unmatched_ = 0;  // switches_[next_unmatched_..] still wait for truth
};

}  // namespace robodds::evaluator
