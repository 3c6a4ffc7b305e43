#pragma once
// Paper-2 (circumnavigation) metrics of the evaluator, fed sample by sample: formation settle
// time and tail errors per phase, range-rate observer errors against the truth rate, and how
// often the truth range acceleration broke the observer's bound b. Pure (std only): samples are
// identified by their simulation step, every time below is step * step_s in s; distances in m,
// angles in rad (the spacing figures in deg), rates in m/s.
//
// What is kept: per robot the truth samples an estimate of the same step may still need (at most
// kTruthCapacity), per robot its assignments (one per event), per phase the last 200 s of
// per-step sums (kTailWindowS / step_s entries), never the whole history.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sim/evaluator/consistency.hpp"

namespace robodds::evaluator {

/// The tolerances and windows of the metrics (issue 10's acceptance table), in one place.
namespace circumnavigation {
inline constexpr double kSettleRadiusTolM = 5.0;     // |r - R| at or below this: on the circle
inline constexpr double kSettleGapTolDeg = 5.0;      // |gap - 360/n| at or below this: spaced
inline constexpr double kTailWindowS = 200.0;        // "last 200 s of each phase"
inline constexpr double kTransientFromS = 5.0;       // transient window after each start
inline constexpr double kTransientToS = 200.0;
inline constexpr double kConvergenceTolMps = 0.2;    // |error| at or below this counts as converged
inline constexpr double kConvergenceHoldS = 200.0;   // ... when it holds this long
// ... outside the paper's assumption: once the error has held within the tolerance this long, an
// excursion while the truth |r''| exceeds the observer's bound b, or within kBoundRecoveryS after,
// does not break the hold (paper 2's convergence assumes |r''| <= b; issue 27, finding 6).
inline constexpr double kConvergenceConfirmS = 5.0;
inline constexpr double kBoundRecoveryS = 5.0;
inline constexpr double kRestartWindowS = 10.0;      // max error window after a restart
inline constexpr std::size_t kTruthCapacity = 4096;  // truth samples kept per robot for late estimates
}  // namespace circumnavigation

/// One truth sample of a robot's plant state.
struct PlantSample {
  std::uint64_t step = 0;
  double x = 0.0;      // m
  double y = 0.0;      // m
  double theta = 0.0;  // rad
  double v = 0.0;      // m/s, applied forward speed
  double omega = 0.0;  // rad/s, applied turn rate
};

/// A robot's assignment from `step` on (the mission's TargetAssignment).
struct TargetAssignmentInfo {
  bool active = false;  // false: no target (left the mission); the robot counts nowhere
  std::uint32_t target_id = 0;
  double target_x = 0.0;        // m
  double target_y = 0.0;        // m
  double desired_radius = 0.0;  // m
};

/// One range-rate estimate of a robot about target `target_id`.
struct RateEstimateSample {
  std::uint64_t step = 0;
  std::uint32_t target_id = 0;
  double range_rate = 0.0;  // m/s
  bool valid = false;
  bool restarted = false;
  double range_rate_std = 0.0;  // m/s, the std the observer reports for range_rate (issue 27)
};

enum class ObserverKind { kSta = 0, kLinear = 1, kKalman = 2 };
inline constexpr std::size_t kObserverKinds = 3;
/// "sta", "linear": the summary.json key of the kind.
const char* observer_kind_name(ObserverKind kind);

/// Truth range rate and range acceleration of a unicycle about a fixed target.
struct RangeDerivatives {
  double r = 0.0;      // m
  double rdot = 0.0;   // m/s
  double rddot = 0.0;  // m/s^2
};
/// From the plant state: rdot = u . pdot, r'' = (|pdot|^2 - rdot^2) / r + u . pddot, with
/// pddot = v_dot along the heading plus v omega normal to it (u = (p - T) / r).
RangeDerivatives range_derivatives(double x, double y, double theta, double v, double omega, double v_dot,
                                   double target_x, double target_y);

/// Root mean square of what was added; nullopt when nothing was.
struct SquareSum {
  double sum_squares = 0.0;
  std::size_t count = 0;
  void add(double e) { sum_squares += e * e; ++count; }
  void add(const SquareSum& other) { sum_squares += other.sum_squares; count += other.count; }
  std::optional<double> rms() const;
};

/// Per-step sums of the last `window_steps` steps before the newest one added: what "the last
/// 200 s" needs, whatever order the steps come in (a step older than the window is dropped).
class TailSum {
 public:
  explicit TailSum(std::uint64_t window_steps) : window_steps_(window_steps) {}
  void add(std::uint64_t step, double error);
  /// Sum over the steps in (end_step - window_steps, end_step].
  SquareSum over_window_ending(std::uint64_t end_step) const;
  std::size_t size() const { return steps_.size(); }

 private:
  std::uint64_t window_steps_;
  std::deque<std::pair<std::uint64_t, SquareSum>> steps_;  // step order, one entry per step
  std::uint64_t newest_ = 0;
};

struct PhaseMetrics {
  double start_s = 0.0;                   // the phase's first step, s
  double settle_time_s = -1.0;            // s after start_s; -1: not settled at the phase's end
  bool evaluated = false;                 // a step with an active robot was evaluated (else nobody took part)
  /// The tail figures below are of a settled formation only: the last kTailWindowS of the phase
  /// (or the whole phase, when shorter) all lie after its settling. Otherwise they are nullopt and
  /// this says why ("never settled", "settled only 120 s before the phase's end"): a tail RMSE over
  /// the approach would be misleading (issue 27). Empty: settled, or no data.
  std::string not_settled;
  std::optional<double> radius_rmse_m;    // last kTailWindowS of the phase, pooled over robots
  std::optional<double> spacing_rmse_deg; // same, pooled over the gaps of every team
};

struct ObserverMetrics {
  std::optional<double> transient_rmse_mps;          // valid samples 5-200 s after each start
  std::optional<double> steady_rmse_mps;             // last 200 s of each phase, pooled
  /// Max over robots of the time from the robot's first estimate to the first valid one from
  /// which the error stays within kConvergenceTolMps for kConvergenceHoldS, excursions while the
  /// truth |r''| exceeds b (and kBoundRecoveryS after) excused once it held kConvergenceConfirmS.
  /// -1: a robot never converged.
  double convergence_s = -1.0;
  /// Valid samples outside kConvergenceTolMps excused that way (the bound b was broken), pooled.
  std::size_t convergence_excused = 0;
  std::optional<double> max_error_after_restart_mps; // nullopt: no restart
  std::size_t restarts = 0;
  std::size_t matched = 0;  // estimates compared with truth
  /// Issue 27: valid estimates whose error is outside 3 reported stds (consistency.hpp), from
  /// each robot's first sample, while its robot is active; pooled over the robots.
  ConsistencyStats consistency;
};

struct CircumnavigationSummary {
  std::vector<PhaseMetrics> phases;  // phase 1 first
  ObserverMetrics observers[kObserverKinds];
  std::optional<double> range_accel_over_b_fraction;  // nullopt: no truth sample of an active robot
  std::size_t range_accel_samples = 0;
};

/// The metrics of one run. Phases are the intervals between assignment changes (the first
/// assignment starts phase 1); the team of a target in a phase is the active robots assigned to
/// it. A step is evaluated when every robot's truth has passed it (or at finish()), with the
/// assignments in force at that step: an assignment must arrive before the truth of the step
/// after its own. Estimates are compared with truth at the same step, whenever they arrive
/// within kTruthCapacity steps of it; each robot's estimates of one kind come in step order.
class CircumnavigationMetrics {
 public:
  /// `b`: the observer's bound on |r''| (range_accel_over_b_fraction).
  CircumnavigationMetrics(double step_s, double b);

  /// Truth of `kind` is kept for matching only when it is expected (the topic is recorded).
  void expect_observer(ObserverKind kind) { expected_[static_cast<std::size_t>(kind)] = true; }
  bool expects(ObserverKind kind) const { return expected_[static_cast<std::size_t>(kind)]; }
  double b() const { return b_; }
  void add_truth(std::uint32_t robot, const PlantSample& sample);
  void add_assignment(std::uint32_t robot, std::uint64_t step, const TargetAssignmentInfo& assignment);
  void add_estimate(ObserverKind kind, std::uint32_t robot, const RateEstimateSample& estimate);
  /// Evaluates the steps every robot's truth has passed and matches the estimates they allow.
  void update();
  /// The run is over: evaluates every step left and matches what can be.
  void finish();

  CircumnavigationSummary summary() const;
  /// Truth samples kept over all robots (memory check).
  std::size_t kept_truth() const;

 private:
  struct TruthEntry {
    PlantSample s;
    bool closed = false;  // evaluated: the fields below are set
    bool active = false;
    std::size_t phase = 0;  // 1-based; 0: before any assignment
    bool over_b = false;    // active, and its truth |r''| exceeds b
  };
  struct Stream {  // one robot's estimates of one kind
    std::deque<RateEstimateSample> pending;
    bool any = false;
    std::uint64_t floor = 0;  // step of the last one handled; earlier ones are out of order
    std::uint32_t last_target = 0;
    std::uint64_t start_step = 0;  // the latest start (first sample, restart, target change)
    bool restart_waiting = false;  // a restart whose first valid sample has not come yet
    bool restart_window = false;
    std::uint64_t restart_from = 0;
    std::uint64_t first_step = 0;
    bool converged = false;
    bool run_open = false;  // a run of samples within the tolerance is going on
    std::uint64_t run_from = 0;
    double convergence_s = -1.0;
    std::uint64_t excused_until = 0;  // an excursion up to this step is excused (|r''| > b recently)
    bool any_over_b = false;          // excused_until is set
    std::size_t excused = 0;          // samples excused
    std::optional<ConsistencyTracker> consistency;  // from the first estimate matched with truth
  };
  struct Robot {
    std::deque<TruthEntry> truth;  // step order; the first `closed` are evaluated
    std::size_t closed = 0;
    std::vector<std::pair<std::uint64_t, TargetAssignmentInfo>> assignments;  // step order
    bool has_previous = false;  // the last evaluated sample, for v_dot
    std::uint64_t previous_step = 0;
    double previous_v = 0.0;
    Stream streams[kObserverKinds];
  };
  struct Phase {
    std::uint64_t start_step = 0;
    std::uint64_t last_step = 0;
    bool any = false;           // a step of the phase was evaluated
    bool settled = false;       // every step from settled_from on was within the tolerances
    std::uint64_t settled_from = 0;
    TailSum radius;
    TailSum spacing;
    std::vector<TailSum> observer;  // per kind
  };
  struct ObserverTotals {
    SquareSum transient;
    std::optional<double> max_after_restart;
    std::size_t restarts = 0;
    std::size_t matched = 0;
  };

  const TargetAssignmentInfo* assignment_at(const Robot& robot, std::uint64_t step) const;
  std::size_t phase_of(std::uint64_t step) const;
  Phase& phase(std::size_t index);
  bool close_next(bool all);
  void close_step(std::uint64_t step);
  void match(ObserverKind kind, Robot& robot);
  void handle(ObserverKind kind, Stream& stream, const RateEstimateSample& e, const TruthEntry* truth);
  void trim(Robot& robot);
  std::uint64_t steps(double seconds) const;

  double step_s_;
  double b_;
  bool expected_[kObserverKinds] = {false, false, false};
  std::map<std::uint32_t, Robot> robots_;
  std::map<std::uint32_t, std::pair<double, double>> targets_;  // id -> (x, y), from the assignments
  std::vector<std::uint64_t> boundaries_;  // phase start steps, ascending
  std::vector<Phase> phases_;
  bool any_closed_ = false;
  std::uint64_t closed_through_ = 0;  // every step <= this is evaluated (when any_closed_)
  ObserverTotals totals_[kObserverKinds];
  std::size_t accel_samples_ = 0;
  std::size_t accel_over_b_ = 0;
};

}  // namespace robodds::evaluator
