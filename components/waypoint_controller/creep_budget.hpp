#pragma once
// Issue 24 (finding 3): when a robot may drive without a usable pose estimate. Creeping ahead
// reveals the heading to a position-fix filter at the start of a run; anywhere else it is blind
// driving. Pure (std only, time in plain seconds); one budget per robot.

namespace robodds::waypoint_controller {

/// The bounds of the creep before the first valid estimate of a run. No defaults here: the node's
/// parameter table has them (invalid_estimate_creep_max_m, invalid_estimate_creep_limit_s).
struct CreepLimits {
  double max_distance_m = 0.0;  // m: commanded distance (|v| integrated over the steps)
  double max_time_s = 0.0;      // s: from the first creeping step
  int max_restarts = 0;         // estimator restarts that may each grant a new budget in a run
  /// Issue 27: with fixes noisier than configured the estimator learns the heading more slowly and
  /// may need more creeping than one budget; the controller does not know the fix noise, but it
  /// sees the estimate's heading std falling. When a limit is reached and the heading std fell by
  /// at least min_progress (a fraction) since the start of this budget, one more budget (distance
  /// and time from zero) is granted, at most max_extensions times per budget. 0 = none.
  int max_extensions = 0;
  double min_progress = 0.0;
  /// Issue 27 ("missions degrade gracefully"): an estimate that turns invalid after it was valid,
  /// while its position is still known (position std sqrt(var x + var y) below
  /// relearn_max_position_std_m: the fixes still hold it, only the heading spread grew past the
  /// estimator's keep limit), grants a new budget: a robot that stands still cannot bring its heading
  /// spread down again (kidnap_10m seed 4 stood for good 14 s after a recovery with a true heading
  /// error of 1-7 deg), a creeping one does, as at the start of a run. At most max_relearns times
  /// in a row without a way-point reached in between (a robot whose estimate keeps failing on one
  /// leg stops, and says so). 0 = none (before: never after a valid estimate).
  int max_relearns = 0;
  double relearn_max_position_std_m = 0.0;  // m
};

/// Why a creep step is refused (kAllowed: it is not).
enum class CreepVerdict {
  kAllowed,
  kAfterValidEstimate,  // and no relearn: off, or the position not known well enough
  kRelearnsSpent,       // after a valid estimate, max_relearns used up on this leg
  kMissionDone,
  kDistanceSpent,
  kTimeSpent
};

/// What is left of one robot's creep. Creeping is allowed only until the first valid estimate of
/// the run (or of an estimator restart, at most max_restarts times, or of a relearn: an estimate
/// invalid again with its position known, CreepLimits::max_relearns), never once the mission is
/// done, and within both limits: the distance is the commanded
/// speed integrated over the creeping steps (the controller has no pose to measure it with).
/// The last allowed step may pass max_distance_m by at most one step's |v|·period.
class CreepBudget {
 public:
  explicit CreepBudget(const CreepLimits& limits) : limits_(limits) {}

  /// The estimate was valid (the controller tracked): no creeping for the rest of the run, or until
  /// the estimator restarts.
  void estimate_was_valid() { had_valid_ = true; }

  /// The estimator started again from its latest inputs alone (PoseEstimate.restarts rose): a lost
  /// filter redrawn knows the robot's position from the fixes but not its heading, as at the start
  /// of a run. While max_restarts is not used up this grants one new budget (distance and time
  /// from zero, creeping until the next valid estimate); true when it did. A stale or flickering
  /// estimate is no restart: it never grants one.
  bool estimator_restarted();

  /// Whether the robot may creep at `time_s` (s, the step's time); `mission_done`: its last
  /// way-point was reached. The first allowed call starts the time limit. At a limit, an extension
  /// is granted when the heading std last observed fell enough since the budget started
  /// (CreepLimits::max_extensions).
  CreepVerdict check(double time_s, bool mission_done);

  /// The (invalid) estimate's heading std now (rad): what an extension judges progress by.
  void observe_heading_std(double std_rad);
  /// The (invalid) estimate's position std now (m, sqrt(var x + var y)): what a relearn needs.
  /// `inputs_stale`: the estimator says its own sensors went quiet (real time; the sensor host may
  /// be dead): the position counts as not known, whatever its std says (issue 24: no blind creeping).
  void observe_position_std(double std_m, bool inputs_stale);
  /// A way-point was reached: the relearns in a row start from zero.
  void waypoint_reached() { relearns_ = 0; }
  /// Relearns granted since the last way-point reached.
  int relearns() const { return relearns_; }
  /// Extensions granted since the last budget started.
  int extensions() const { return extensions_; }

  /// The creep command of `v_mps` (m/s) went out and is held for `period_s` (s).
  void crept(double v_mps, double period_s);

  double distance_m() const { return distance_m_; }

 private:
  CreepLimits limits_;
  bool had_valid_ = false;
  int restarts_granted_ = 0;
  bool started_ = false;
  double started_s_ = 0.0;   // s, time of the first creeping step
  double distance_m_ = 0.0;  // m, commanded so far
  int extensions_ = 0;
  int relearns_ = 0;                      // since the last way-point reached
  double position_std_m_ = -1.0;          // m, last observed (< 0: none yet)
  double heading_std_rad_ = -1.0;         // rad, last observed (< 0: none yet)
  double budget_start_std_rad_ = -1.0;    // rad, observed when this budget (or extension) started
};

/// A short reason for logs ("" for kAllowed).
const char* describe(CreepVerdict verdict);

}  // namespace robodds::waypoint_controller
