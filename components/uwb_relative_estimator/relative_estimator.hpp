#pragma once
// One robot's relative-pose estimator of paper 3 (issue 11): every 10 Hz epoch, for each peer j,
// the pose of j in this robot's (i's) body frame by five stages, each kept apart so that all can be
// published and compared in one run:
//   uwb          eq. (1), one solve per epoch from that epoch's K x L ranges (RelativePoseTracker:
//                warm start, cold-start recovery; only kOk is valid);
//   window       eq. (2), one sliding-window pose graph of this robot and all its peers (robot 0 =
//                this robot), odometry edges between epochs and the uwb stage's kOk poses as edges,
//                plus, as the paper's server that has every robot's data, the eq. (1) poses between
//                pairs of peers ("links": ranges measured by the lower id of the two), which close
//                loops in the graph;
//   pf           eq. (3)-(6), one filter per peer: predicted by both robots' odometry (eq. 4),
//                weighted by the window's estimate (eq. 5-6); started around the window's first
//                estimate, restarted around it when a fix ends a gap of more than
//                restart_after_gap_s without one (the window too drifted on odometry meanwhile);
//   pf_baseline  the paper's [22]: the same filter weighted directly by the K x L ranges,
//                (re)started from a kOk solve at the first one and after such a gap;
//                both filters also restarted when their check against the eq. (1) fixes finds
//                them lost (InnovationMonitor::lost; counts().filter_restarts / baseline_restarts);
//   odometry     dead reckoning of the relative pose from both odometries (the paper's first row),
//                from a known start or, without one, from the first kOk solve;
//   tc           beyond the paper (issue 28): TightlyCoupledWindow, one per peer, on this epoch's raw
//                ranges and both odometries with the range biases as states, started (and
//                restarted) from a kOk solve.
// Pure: Eigen + std + Ceres, time in plain seconds; wall-clock compute time per stage is measured
// here (std::chrono::steady_clock) and returned, for the node to report.
//
// Ranges of an epoch: the newest frame the node has for the peer (none: lost, out of range). A
// frame of the wrong shape, with a negative or non-finite range is rejected by the tracker and used
// by no stage (counted). Odometry increments must be finite and the time must not go back
// (std::invalid_argument, state untouched); past those checks step() does not throw.
#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "common/model/pose2.hpp"
#include "common/model/uwb_array.hpp"
#include "common/random.hpp"
#include "components/uwb_relative_estimator/filter_error_covariance.hpp"
#include "components/uwb_relative_estimator/fix_track_check.hpp"
#include "components/uwb_relative_estimator/relative_estimator_params.hpp"
#include "components/uwb_relative_estimator/relative_pf.hpp"
#include "components/uwb_relative_estimator/relative_pose_covariance.hpp"
#include "components/uwb_relative_estimator/relative_pose_tracker.hpp"
#include "components/uwb_relative_estimator/sliding_window.hpp"
#include "components/uwb_relative_estimator/tightly_coupled_window.hpp"
#include "components/uwb_relative_estimator/worker_pool.hpp"

namespace robodds::uwb_relative_estimator {

enum class Stage { kUwb = 0, kWindow, kPf, kPfBaseline, kOdometry, kTc };
inline constexpr std::size_t kStageCount = 6;
/// "uwb", "window", "pf", "pf_baseline", "odometry", "tc" (topic suffixes and metric names).
const char* stage_name(Stage stage);

struct StageEstimate {
  model::Pose2 pose;  // peer in this robot's body frame: x forward, y left (m), theta CCW (rad)
  bool valid = false;
  /// Covariance of [x, y, theta] (m^2, m rad, rad^2): the filters': the covariance of their error
  /// when their measurements' errors last as long as the range errors do (FilterErrorCovariance;
  /// the particles' spread counts every epoch's measurement as new, and is not reported), plus the
  /// eq. (1) fixes' unexplained median innovation (InnovationMonitor); uwb: scaled by its check of the
  /// fixes against earlier fixes dead-reckoned by odometry (FixTrackCheck); every UWB stage: each range
  /// an outlier's own variance when beyond outlier_sigma, a bias per UWB node (node_bias_std_m,
  /// configured: the fit absorbs it), plus the bearing's curvature; uwb: the least-squares fit's (range_fix_covariance, with the range noise estimated from the
  /// residuals); window: the same at the window's pose (the fixes' errors last longer than the
  /// window, so averaging them is given no credit); odometry: propagated from the start (zero
  /// when known, else the first fix's) with the window's odometry stds per epoch. Zero when not
  /// valid.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

struct PeerSetup {
  std::uint32_t id = 0;          // the peer's robot id (names its random streams and messages)
  model::UwbArray array;         // the peer's node positions in its body frame
  /// The peer's pose in this robot's frame at the first epoch, when known (the odometry stage
  /// starts from it; without it, from the first valid eq. 1 solve).
  std::optional<model::Pose2> known_start;
};

struct PeerEpoch {
  /// The peer's motion since the previous epoch, in its own frame at the previous epoch.
  model::Pose2 odometry_increment;
  /// K x L ranges of this epoch (row k: node k of this robot; column l: node l of the peer);
  /// nullopt: no frame (lost, out of range).
  std::optional<Eigen::MatrixXd> ranges_m;
};

struct PeerResult {
  std::array<StageEstimate, kStageCount> stages;
  bool had_ranges = false;  // a frame was given
  TrackStatus uwb_status = TrackStatus::kRejected;  // meaningful when had_ranges
  std::string uwb_reason;   // why the eq. (1) estimate is not valid (empty when it is)
};

struct EpochResult {
  std::vector<PeerResult> peers;                 // in the order of the constructor's peers
  /// Wall-clock compute time of each stage, ms: the sum of its pieces (per peer, per link), which
  /// may run side by side (params threads > 1), so that together they may exceed cycle_ms.
  std::array<double, kStageCount> stage_ms{};
  double cycle_ms = 0.0;  // wall-clock time of the whole step(), ms
};

struct EstimatorCounts {
  std::uint64_t epochs = 0;
  std::uint64_t frames_missing = 0;      // peer epochs without a frame
  std::uint64_t window_not_converged = 0;  // optimisations Ceres did not report converged
  std::uint64_t filter_restarts = 0;     // pf filters restarted by their lost-filter check
  std::uint64_t baseline_restarts = 0;   // pf_baseline filters restarted by theirs
};

/// Two peers (indices into the constructor's peers, first < second) whose ranges also enter the
/// window: the first measures the second.
struct PeerLink {
  std::size_t first = 0;
  std::size_t second = 0;
};

class RelativeEstimator {
 public:
  /// Throws std::invalid_argument naming the problem: invalid params (the key), no peers, a peer
  /// twice, an array that fails model::check_array ("own_array" / "peer <id> array").
  /// `seed` seeds every peer's two filters (streams derived from it and the peer id).
  RelativeEstimator(model::UwbArray own_array, std::vector<PeerSetup> peers, RelativeEstimatorParams params,
                    std::uint64_t seed);
  ~RelativeEstimator();
  RelativeEstimator(RelativeEstimator&&);
  RelativeEstimator& operator=(RelativeEstimator&&);

  /// One epoch at `time_s` (non-decreasing): `own_increment` is this robot's motion since the
  /// previous epoch in its own frame, `peers` one entry per peer in the constructor's order,
  /// `link_ranges` empty (no link measured) or one entry per links() (the first peer's nodes in
  /// rows; nullopt: no frame). Throws std::invalid_argument (nothing changed) on a wrong count or
  /// a non-finite increment.
  EpochResult step(double time_s, const model::Pose2& own_increment, const std::vector<PeerEpoch>& peers,
                   const std::vector<std::optional<Eigen::MatrixXd>>& link_ranges = {});

  const std::vector<PeerSetup>& peers() const { return setups_; }
  /// Every pair of peers, (0, 1), (0, 2), ..., (1, 2), ...: the order of step()'s link_ranges.
  const std::vector<PeerLink>& links() const { return links_; }
  /// Eq. (1) status counts of link `index` (links() order).
  const TrackerCounts& link_tracker_counts(std::size_t index) const { return link_trackers_.at(index).counts(); }
  const EstimatorCounts& counts() const { return counts_; }
  /// The independent range std (m) estimated for peer `index` (constructor order): the running
  /// median of its eq. (1) residual stds, at least uncertainty.range_std_floor_m.
  double range_noise_std_m(std::size_t index) const { return peers_.at(index).range_noise.std_m(); }
  /// Eq. (1) status counts of peer `index` (constructor order).
  const TrackerCounts& tracker_counts(std::size_t index) const { return peers_.at(index).tracker.counts(); }

 private:
  struct PeerState {
    RelativePoseTracker tracker;
    RelativePoseFilter pf;
    RelativePoseFilter baseline;
    RandomEngine pf_random;
    RandomEngine baseline_random;
    RangeNoiseLevel range_noise;  // independent range std seen in this peer's eq. (1) residuals
    FilterErrorCovariance pf_error;        // what the pf stage reports
    FilterErrorCovariance baseline_error;  // what the pf_baseline stage reports
    InnovationMonitor pf_check;        // the filters against the eq. (1) fixes
    InnovationMonitor baseline_check;
    model::Pose2 pf_pose;        // the filters' estimates of the previous epoch (where their
    model::Pose2 baseline_pose;  // error covariances are propagated from)
    std::optional<model::Pose2> odometry_pose;
    Eigen::Matrix3d odometry_covariance = Eigen::Matrix3d::Zero();
    std::deque<bool> window_edges;  // per epoch in the window: an eq. (1) edge to this peer
    /// Per epoch in the window: the per-range variances its eq. (1) edge reported (empty: none).
    std::deque<Eigen::VectorXd> window_variances;
    /// How the range errors reach the window's pose of this epoch (the pf's measurement);
    /// window_mapped false when there is none.
    RangeErrorMap window_error;
    bool window_mapped = false;
    Eigen::VectorXd fix_variances;  // this epoch's eq. (1) per-range variances (empty: no ok fix)
    std::optional<double> last_fix_s;     // last epoch with a valid eq. (1) pose (the window's edges)
    std::optional<double> last_frame_s;   // last epoch with an accepted frame (the baseline's input)
    /// This epoch's eq. (1) covariance from its independent range errors alone (what the filters
    /// do not share with the fix: their lost-filter test).
    Eigen::Matrix3d fix_own_covariance = Eigen::Matrix3d::Zero();
    /// The uwb stage's check of its fixes over time (FixTrackCheck): scales what it reports.
    FixTrackCheck fix_check;
    /// The odometry stage's check against the eq. (1) fixes: a dead reckoning that drifted beyond
    /// its covariance (wheel slips grow as t, the propagated white noise as sqrt(t)) says so.
    InnovationMonitor odometry_check;
    /// This epoch's eq. (1) covariance as the error model gives it, before fix_check's scaling
    /// (what the filters' InnovationMonitor compares their estimates with).
    Eigen::Matrix3d fix_model_covariance = Eigen::Matrix3d::Zero();
    /// The tc stage's own check against the eq. (1) fixes, as the filters' (tc.innovation_check).
    InnovationMonitor tc_check;
    /// tc's restarts when tc_check last saw it (a restarted tc is a new estimate: the check forgets).
    int tc_restarts = 0;
    /// tc's reported estimates of the last tc.jump_check_epochs epochs, each dead-reckoned to the
    /// latest epoch with its covariance propagated (newest last; empty: tc not valid at the last
    /// epoch), the latest's time, and the covariance tc's own jumps added (decaying with
    /// uncertainty.range_common_time_s).
    std::deque<std::pair<model::Pose2, Eigen::Matrix3d>> tc_kept;
    double tc_time_s = 0.0;
    Eigen::Matrix3d tc_jump = Eigen::Matrix3d::Zero();
  };

  /// Peer k's eq. (1) solve and what the uwb stage reports; its odometry stage.
  void run_uwb(std::size_t k, double time_s, const model::Pose2& own_increment, const PeerEpoch& input, PeerResult& out);
  /// tc's jump check (tc.jump_check): what its own jumps beyond its reported covariance add to it.
  Eigen::Matrix3d tc_jump_term(PeerState& peer, double time_s, const model::Pose2& own_increment,
                               const model::Pose2& peer_increment, const StageEstimate& estimate) const;
  void run_odometry(std::size_t k, const model::Pose2& own_increment, const PeerEpoch& input, PeerResult& out);
  void run_window(const model::Pose2& own_increment, const std::vector<PeerEpoch>& peers,
                  const std::vector<PairMeasurement>& link_edges, EpochResult& result);
  /// This epoch's uwb estimate with the error model's covariance (before the fix-track check's
  /// scaling): what the filters' checks compare with (their InnovationMonitor has its own test).
  static StageEstimate model_fix(const PeerState& peer, const PeerResult& result);
  /// Peer `k` has an eq. (1) edge in the window: its poses there rest on a measurement.
  bool placed(std::size_t k) const;
  /// The tc stage of peer k (issue 28).
  void run_tc(std::size_t k, double time_s, const model::Pose2& own_increment, const PeerEpoch& input, PeerResult& out);
  /// The filters of peer k; `restarts` counts their restarts by the lost-filter check.
  void run_pf(std::size_t k, double time_s, double dt_s, const model::Pose2& own_increment, const PeerEpoch& input,
              PeerResult& result, std::uint64_t& restarts);
  void run_baseline(std::size_t k, double time_s, double dt_s, const model::Pose2& own_increment, const PeerEpoch& input,
                    PeerResult& result, std::uint64_t& restarts);

  model::UwbArray own_array_;
  std::vector<PeerSetup> setups_;
  RelativeEstimatorParams params_;
  std::vector<PeerState> peers_;
  std::vector<PeerLink> links_;
  std::vector<RelativePoseTracker> link_trackers_;  // one per link
  /// Started at the first epoch with a valid eq. (1) pose of any peer; a peer whose poses in it are
  /// a guess (no edge of it in the window yet) is placed by its first edge (place_robot).
  std::optional<SlidingWindowGraph> window_;
  std::optional<double> last_time_s_;
  EstimatorCounts counts_;
  std::vector<TightlyCoupledWindow> tc_;  // the tc stage of each peer (constructor order; issue 28)
  std::unique_ptr<WorkerPool> pool_;      // params threads (issue 29)
};

}  // namespace robodds::uwb_relative_estimator
