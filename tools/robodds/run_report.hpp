#pragma once
// The short report `robodds run` prints at the end (issue 26): status and reason, simulated and
// wall time, the metrics modules' headline lines (sim/evaluator/module/headline.hpp), rejected
// and adjusted inputs and warnings only when there are any, and where the outputs are. Pure:
// summary.json's leaves in, text out (`--verbose` prints summary_table() instead).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sim/evaluator/module/headline.hpp"
#include "tools/robodds/summary_table.hpp"

namespace robodds {

struct RunReportInput {
  std::vector<SummaryLeaf> summary;  // the leaves of summary.json (summary_leaves()); empty: none
  std::string summary_note;          // with no leaves: why (no evaluator, unreadable file)
  evaluator::Headline headline;      // every module's lines, in summary order
  std::optional<std::uint64_t> ticks;  // the runner's (RunStats); else summary.json's "steps"
  std::optional<double> wall_s;        // the runner's; else summary.json's run.wall_time_s
  double step_s = 0.0;                 // s per step
  std::size_t warnings_logged = 0;     // warnings this process wrote to stderr during the run
  std::string out_dir;
  std::size_t csv_files = 0;
  std::size_t plot_files = 0;
};

/// Most metric lines the report prints, the mission line (summary.json "mission") included; the
/// rest are counted on one line (summary.json has them).
inline constexpr std::size_t kMaxHeadlineLines = 9;

/// The report, one string per line (no newlines): at most kMaxHeadlineLines + 6 = 15 lines.
std::vector<std::string> run_report_lines(const RunReportInput& input);

/// `value` to `significant` figures without an exponent and without trailing zeros
/// (283.14 -> "283", 0.0063229 -> "0.00632", 1.5 -> "1.5", 0 -> "0").
std::string round_significant(double value, int significant);

/// The headline lines `headline` gives for `summary` ("label  text"), in order; a line whose
/// keys are missing is left out. `used_paths`, if given, gets the paths of the leaves the lines
/// show (e.g. "metrics.pf_rmse_m"; `robodds sweep` prints those metrics' rows).
std::vector<std::string> headline_lines(const evaluator::Headline& headline, const std::vector<SummaryLeaf>& summary,
                                        std::vector<std::string>* used_paths = nullptr);

}  // namespace robodds
