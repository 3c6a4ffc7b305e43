#pragma once
// A metrics module's headline figures: the few lines of summary.json's "metrics" that `robodds
// run` prints at the end of a run (tools/robodds/run_report.hpp renders them). Each module names
// its own in its registration (ROBODDS_REGISTER_METRICS_MODULE), next to the code that writes the
// keys, so the CLI knows no mission kind.

#include <string>
#include <vector>

namespace robodds::evaluator {

/// One line of the short report: `label`, then `text` with each {key} replaced by the leaf `key`
/// of the object `scope` below "metrics" (numbers to 3 significant figures, {key:N} to N; a time
/// "_s" of -1 reads "never", the " s" after it dropped). The line is left out when a key is
/// missing (the topic it needs was not recorded). A "*" in `scope` matches each object at that
/// level (a line per match, in file order), and {*} in the label or text stands for the matched
/// name.
struct HeadlineLine {
  std::string label;  // e.g. "PF RMSE", "phase {*}"
  std::string scope;  // "" (the top level of "metrics"), "observer.sta", "phase*", "stages.*"
  std::string text;   // e.g. "{pf_rmse_m} m position, {heading_rmse_deg} deg heading"
};

using Headline = std::vector<HeadlineLine>;

}  // namespace robodds::evaluator
