#pragma once
// After a failed run: <out>/summary.json says so, whoever wrote it.

#include <string>

namespace robodds {

/// Makes `out_dir`/summary.json say "status": "failed" with "reason": `reason` (the error line
/// of the run). The evaluator's own summary (written when its host learnt of the failure) keeps
/// its metrics and gets this reason, the run's cause as the runner saw it, in place of its own
/// (e.g. "interrupted by a signal" when the runner stopped it). Without one (no evaluator, or its
/// process died), a summary of the status and the reason alone is written. Never throws: a
/// failure to write is logged as a warning (the run's own error is the one to report).
void record_failed_run(const std::string& out_dir, const std::string& reason);

/// The text of summary.json `existing` (empty: none) with the status "failed" and `reason`.
std::string failed_summary_text(const std::string& existing, const std::string& reason);

}  // namespace robodds
