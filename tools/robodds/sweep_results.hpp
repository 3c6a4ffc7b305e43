#pragma once
// `robodds sweep`: the outcome of each run and the per-combination statistics of every metric
// of summary.json (mean, standard deviation, min, max, 95 % confidence interval of the mean).

#include <string>
#include <utility>
#include <vector>

#include "common/sample_stats.hpp"
#include "tools/robodds/summary_table.hpp"
#include "tools/robodds/sweep_plan.hpp"

namespace robodds::sweep {

struct RunOutcome {
  PlannedRun run;
  bool ok = false;
  int exit_code = -1;  // of `robodds run` (128 + signal if killed; -1: not run)
  double wall_s = 0.0;
  std::string error;   // why it failed (its log's last error line), empty if ok
  /// Never started, or stopped by the sweep's interruption before it finished: neither ok nor
  /// failed (the tables say "not run"; `robodds sweep ... --resume DIR` runs it).
  bool not_run = false;
  std::vector<std::pair<std::string, double>> metrics;  // "metrics." leaves of summary.json that are finite numbers
};

/// The finite numeric leaves under "metrics" of the summary.json at `path`, their paths without
/// the "metrics." prefix, in file order. Throws std::runtime_error naming the file if unreadable.
std::vector<std::pair<std::string, double>> read_metrics(const std::string& path);

/// The same from leaves already read (summary_leaves()).
std::vector<std::pair<std::string, double>> metrics_of(const std::vector<SummaryLeaf>& leaves);

/// summary_table.hpp's: such a value is counted, never averaged as a duration.
using ::robodds::is_never;

/// The statistics of one metric over the successful runs of one combination.
struct MetricStats {
  std::size_t combination = 0;
  std::string metric;
  stats::SampleSummary summary;  // over the runs with a value; count 0 when every one was "never"
  std::size_t never = 0;         // runs that reported "never" (is_never), not in `summary`
};

/// Per combination (in order) and metric (in order of first appearance): the statistics over the
/// runs that succeeded and report it, "never" values counted apart. A metric no successful run
/// reports is absent.
std::vector<MetricStats> aggregate(const std::vector<RunOutcome>& outcomes);

/// Every run: index, seed, one column per grid axis, status ("ok", "failed", "not run"), exit code, wall time, error, then one
/// column per metric (empty where a run lacks it).
std::string runs_csv(const std::vector<GridAxis>& axes, const std::vector<RunOutcome>& outcomes);

/// One row per combination and metric: the axes' values, n, mean, std, min, max, ci95 (half width),
/// never (runs that reported "never", not in n; the statistics cells are empty when n is 0).
std::string summary_csv(const std::vector<GridAxis>& axes, const std::vector<MetricStats>& rows);

/// The same as Markdown: a section per combination with its runs done/failed (and not run, if
/// any) and a table.
std::string summary_markdown(const std::vector<GridAxis>& axes, const std::vector<RunOutcome>& outcomes,
                             const std::vector<MetricStats>& rows);

}  // namespace robodds::sweep
