#pragma once
// summary.json as the aligned "key  value" table `robodds run` prints at the end.

#include <string>

namespace robodds {

/// The table of `out_dir`/summary.json: a title line, then one line per number or string with
/// its dotted path (e.g. "metrics.robots.1.pf_rmse_m"). A missing file gives a one-line note
/// (the scenario has no evaluator); an unreadable one a note naming the file and the reason.
std::string summary_table(const std::string& out_dir);

}  // namespace robodds
