#pragma once
// summary.json read back: flattened to dotted paths, and as the aligned "key  value" table
// `robodds run` prints at the end.

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace robodds {

/// One leaf of summary.json: its dotted path (e.g. "metrics.robots.1.pf_rmse_m"), its JSON text
/// (strings in quotes, numbers bare, null for a non-finite figure, lists as [..]) and, for a
/// finite number, its value.
struct SummaryLeaf {
  std::string path;
  std::string json;
  std::optional<double> number;
};

/// The evaluator reports a time that never came as -1 (time_to_final_s, settle_time_s,
/// convergence_s, time_to_valid_s: "-1: never" in sim/evaluator): true for a metric whose name
/// ends in "_s" with that value.
bool is_never(const std::string& metric, double value);

/// The leaves of the JSON file `path`, in file order. Throws std::runtime_error naming the file
/// if it cannot be read or is not a JSON object.
std::vector<SummaryLeaf> summary_leaves(const std::string& path);

/// The table of `out_dir`/summary.json: a title line, then one line per number or string with
/// its dotted path (e.g. "metrics.robots.1.pf_rmse_m"). A missing file gives a one-line note
/// (the scenario has no evaluator); an unreadable one a note naming the file and the reason.
std::string summary_table(const std::string& out_dir);

}  // namespace robodds
