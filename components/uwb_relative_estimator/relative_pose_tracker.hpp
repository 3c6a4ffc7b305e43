#pragma once
// Eq. (1) solved epoch after epoch for one (robot, peer) pair, with recovery from wrong minima (an
// extension: the paper does not say how it starts its LM). Each epoch warm-starts from the previous
// estimate; started 150-180 deg off in heading a warm start ends in a wrong minimum in about a third
// of the cases, which the 32-start cold start of solve_relative_pose() does not. So the tracker
// cold-starts at the first epoch, every cold_start_period_s, after a failed solve and whenever the
// warm start's final cost exceeds cost_ratio x the running median of recent costs. A solve that fails
// or that looks like a wrong minimum is reported (status) and counted, never returned as kOk.

#include <cstdint>
#include <deque>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "common/model/pose2.hpp"
#include "common/param_table.hpp"
#include "components/uwb_relative_estimator/relative_pose_solver.hpp"
#include "common/model/uwb_array.hpp"

namespace robodds::uwb_relative_estimator {

// Units, ranges and one-line descriptions of these fields: tracker_param_table() in
// relative_pose_tracker.cpp (the one source; its doc() prints them). Defaults: the initialisers.
struct TrackerParams {
  double cold_start_period_s = 10.0;
  /// A warm start whose cost exceeds cost_ratio x the running median (and cost_floor_m2) is
  /// re-solved from a cold start; still above it after that, the epoch is kSuspect.
  double cost_ratio = 5.0;
  /// Costs of the last N solves with a finite result (kOk or kSuspect) form the running median,
  /// so that a lasting change of the noise level becomes the new normal after N/2 epochs.
  int cost_median_window = 50;
  /// Costs at or below this never count as a spike (noise-free ranges have costs ~1e-20, and 5x
  /// of that means nothing). 1e-3 m^2 = 1/2 x 16 ranges x (1.1 cm)^2.
  double cost_floor_m2 = 1e-3;
  /// A cold start and the warm start of the same epoch further apart than this disagree: one of
  /// them is a wrong minimum, and the epoch is kSuspect (the lower cost is kept for the next epoch).
  double disagreement_position_m = 0.5;
  double disagreement_heading_rad = 0.35;

  /// Throws std::invalid_argument "key: requirement (got value)".
  void validate() const;
};

/// Keys, units, ranges and descriptions of TrackerParams (defaults: the initialisers above).
const params::ParamTable<TrackerParams>& tracker_param_table();

enum class TrackStatus {
  kOk,        // a valid estimate
  kSuspect,   // solved, but a cold start disagreed with the warm start or the cost stayed high
  kFailed,    // the solver failed (no convergence, non-finite result); the next epoch cold-starts
  kRejected,  // bad input (ranges of the wrong shape, negative or non-finite; time not finite or going back); nothing changed
};

enum class ColdStart {
  kNone,        // warm start only
  kFirst,       // no previous estimate (first epoch, or after a failure)
  kPeriodic,    // cold_start_period_s since the last cold start
  kCostSpike,   // the warm start's cost exceeded the ratio
  kWarmFailed,  // the warm start failed
};

std::string to_string(TrackStatus status);
std::string to_string(ColdStart cold_start);

struct TrackerOutput {
  model::Pose2 pose;  // j in i's frame; meaningful for kOk (and kSuspect: the best fit, not to publish)
  double cost = 0.0;  // final Ceres cost of the kept solve, m^2
  TrackStatus status = TrackStatus::kOk;
  ColdStart cold_start = ColdStart::kNone;
  std::string reason;  // empty for kOk
};

struct TrackerCounts {
  std::uint64_t ok = 0;
  std::uint64_t suspect = 0;
  std::uint64_t failed = 0;
  std::uint64_t rejected = 0;
  std::uint64_t cold_starts = 0;
};

class RelativePoseTracker {
 public:
  /// Throws std::invalid_argument for a bad array (model::check_array with keys "own_array" and
  /// "peer_array"; a node should validate its arrays first with its own keys) or bad params.
  RelativePoseTracker(UwbArray own, UwbArray peer, SolverOptions solver, TrackerParams params);

  /// One epoch: `ranges_m` (K x L, row k: node k of own, column l: node l of peer) measured at
  /// `time_s` (non-decreasing).
  TrackerOutput update(const Eigen::MatrixXd& ranges_m, double time_s);

  const TrackerCounts& counts() const { return counts_; }
  /// The running median of recent costs (nullopt before the first finite solve).
  std::optional<double> cost_median() const;

 private:
  std::optional<std::string> check_input(const Eigen::MatrixXd& ranges_m, double time_s) const;
  TrackerOutput finish(TrackerOutput out);
  double cost_threshold() const;

  UwbArray own_;
  UwbArray peer_;
  SolverOptions solver_;
  TrackerParams params_;
  std::optional<model::Pose2> previous_;  // the warm start of the next epoch
  std::optional<double> last_time_s_;
  double last_cold_start_s_ = 0.0;
  std::deque<double> costs_;
  TrackerCounts counts_;
};

}  // namespace robodds::uwb_relative_estimator
