#pragma once
// summary.json's "status" (how the run ended) and "run" (how it went on the wall clock, kept
// apart from "metrics", which are deterministic).

#include <string>

#include "common/json_writer.hpp"
#include "runtime/component/component.hpp"

namespace robodds::evaluator {

/// How the run ended, for summary.json's "status" (and "reason" when it failed).
struct RunEnd {
  bool completed = true;
  std::string reason;
};

/// "status": "completed" (real time, stopped early by a signal: also "stopped_by": "signal",
/// "stopped_at_s", sim s of the last step, and "stopped_at_utc"); "degraded" when the run reached its end but a host ran without some of
/// its peers or did not report (the "reason" names each); "failed" with the error line that
/// ended the run as "reason".
void write_status_section(JsonWriter& json, const RunEnd& end, const RunFigures& figures);

/// "run": deployment, mode, wall time, ticks per s (by third of the run in lockstep) and the
/// components' compute times per stage ("timing"). A host started on its own knows no
/// deployment and writes none.
void write_run_section(JsonWriter& json, const RunRecording& recording, TimeMode mode);

}  // namespace robodds::evaluator
