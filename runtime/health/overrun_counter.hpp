#pragma once
// Real-time overrun bookkeeping of one host, without a clock: the real-time loop tells it which
// step it ran, which step was due first and when (s since step 0); it counts the due steps the
// loop passed over (skipped) and the steps it ran late, keeps the worst lateness, says when to
// warn (rate-limited) and whether the host exceeded its limit of skipped steps.
//
// Rule (docs/architecture.md, "Real-time overruns"): a step is *due* when a component of the host
// runs at it (its step is a multiple of the component's period). The loop runs the current step
// t = floor(elapsed / step_s); a due step before t that the loop did not run is *missed* (skipped);
// a step that ran more than half a step after its due time is *late*. Lateness of an iteration is
// elapsed - (first due step) * step_s, the delay of the oldest due step it handled.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace robodds {

/// Default of --max-missed-steps: this fraction of the run's steps (rounded down). One place.
/// 5 %: a host that cannot keep up misses far more (41 % in issue 9's finding 6), while the
/// hiccups of a busy shared machine (start-up, a neighbour's build) stay below it.
inline constexpr double kDefaultMaxMissedFraction = 0.05;
/// Seconds between two overrun warnings of one host (the first one is logged at once).
inline constexpr double kOverrunWarnIntervalS = 10.0;

/// The limit of missed steps of a run with `total_steps` steps when none is given.
std::uint64_t default_max_missed_steps(std::uint64_t total_steps);

/// Steps s with from <= s < to at which a component of one of these periods (in steps) is due,
/// i.e. s is a multiple of at least one period. Periods of 0 are ignored.
std::uint64_t due_steps_between(const std::vector<std::uint64_t>& periods, std::uint64_t from, std::uint64_t to);

struct OverrunFigures {
  std::uint64_t ticks = 0;           // steps the loop ran components at
  std::uint64_t missed_steps = 0;    // due steps passed over
  std::uint64_t late_steps = 0;      // steps run more than half a step after their due time
  double worst_lateness_s = 0.0;     // s, largest delay of a due step (0: never late)
};

class OverrunCounter {
 public:
  /// step_s: the scenario step (s); max_missed: the run fails when missed_steps exceeds it.
  OverrunCounter(double step_s, std::uint64_t max_missed);

  /// The loop ran components at `step` at `elapsed_s` (s since step 0); `first_due` (<= step) was
  /// the earliest step a component was due at and `missed` the due steps in [first_due, step) it
  /// passed over (due_steps_between()). Returns true when a warning is due now (the first overrun,
  /// then at most one per kOverrunWarnIntervalS of elapsed time while overruns continue).
  bool ran(std::uint64_t first_due, std::uint64_t step, std::uint64_t missed, double elapsed_s);
  /// The run ended with `missed` due steps after the last step the loop ran not run.
  void missed_at_end(std::uint64_t missed);

  const OverrunFigures& figures() const { return figures_; }
  std::uint64_t max_missed() const { return max_missed_; }
  bool exceeded() const { return figures_.missed_steps > max_missed_; }
  /// "skipped N due steps in all (M steps run, L of them late), worst lateness X s (step S s)".
  std::string totals_text() const;

 private:
  double step_s_;
  std::uint64_t max_missed_;
  OverrunFigures figures_;
  std::optional<double> last_warning_s_;  // elapsed time of the last warning
};

}  // namespace robodds
