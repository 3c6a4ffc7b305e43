#pragma once
// Issue 28, "straight legs": how far the true track strays sideways from each leg of a way-point
// mission. A leg runs from the previous way-point (the first: from the robot's first true
// position) to the way-point the controller aims at; the cross-track error is the true
// position's distance from the leg's line, counted from kLegSettleM along the leg (the turn onto
// it excluded) to the way-point, until the controller says done. Pure: steps are simulation
// steps, distances in m.

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

namespace robodds::evaluator {

/// m along each leg before its cross-track error counts (issue 28: "after the first 10 m").
inline constexpr double kLegSettleM = 10.0;

struct LegDeviationFigures {
  std::size_t samples = 0;            // true positions that counted
  double cross_track_rms_m = 0.0;
  double cross_track_max_m = 0.0;     // largest |cross-track error|
};

/// One robot's cross-track error, accumulated as truth and controller status arrive (in any
/// order between the two topics, each in step order). Keeps the truth samples newer than the
/// newest status (the controller runs slower than the plant), at most kMaxPending of them (a
/// status that stops coming must not make it grow with the run: the oldest are dropped
/// uncounted), and one entry per way-point.
class LegDeviation {
 public:
  /// The mission in force (way-points [x, y] in order); the latest one is measured against.
  void set_mission(std::vector<std::array<double, 2>> waypoints);
  /// The controller at `step` aims at way-point `target_index` (control/status waypoints_reached
  /// until done); `done`: the mission is over, nothing counts from this step on.
  void add_status(std::uint64_t step, std::size_t target_index, bool done);
  static constexpr std::size_t kMaxPending = 4096;
  /// A true position (m, world frame).
  void add_truth(std::uint64_t step, double x_m, double y_m);
  /// nullopt until a sample counted.
  std::optional<LegDeviationFigures> figures() const;

 private:
  struct Truth {
    std::uint64_t step = 0;
    double x = 0.0;
    double y = 0.0;
  };
  void count(const Truth& truth, std::size_t target_index);
  /// Counts the waiting truth of steps <= last_step against the current target.
  void count_pending_through(std::uint64_t last_step);

  std::vector<std::array<double, 2>> mission_;
  bool has_start_ = false;
  std::array<double, 2> start_{};  // m, the first true position: where the first leg starts
  bool has_status_ = false;
  std::uint64_t status_step_ = 0;  // the newest status
  std::size_t target_index_ = 0;   // ... and what it aimed at
  bool done_ = false;
  std::uint64_t done_step_ = 0;
  std::deque<Truth> pending_;      // truth newer than the newest status
  std::size_t samples_ = 0;
  double sum_squares_ = 0.0;
  double max_abs_ = 0.0;
};

}  // namespace robodds::evaluator
