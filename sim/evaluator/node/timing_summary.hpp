#pragma once
// summary.json's run.timing: the components' wall-clock compute times per stage
// (ComponentContext::compute_times(), carried in RunFigures::hosts, across processes on
// run/health). Inside "run", so outside the deterministic comparison of summary.json.

#include <string>
#include <vector>

#include "common/json_writer.hpp"
#include "runtime/component/component.hpp"

namespace robodds::evaluator {

/// One stage over every component that reported it: the largest median, the largest p99 and the
/// largest max of those components (each may come from another component), the samples of all
/// of them, the component with the largest p99 (the first one on a tie) and how many reported.
struct StageFigures {
  std::string stage;
  double median_ms = 0.0;
  double p99_ms = 0.0;
  double max_ms = 0.0;
  std::uint64_t cycles = 0;
  std::string component;
  std::size_t components = 0;
};

/// Every stage of every host's components, in first-reported order (hosts in RunFigures order).
std::vector<StageFigures> stage_figures(const std::vector<HostHealth>& hosts);

/// Writes "timing": {"<stage>": {"cycle_ms_median", "cycle_ms_p99", "cycle_ms_max" (ms rounded to
/// us), "cycles", "component", "components"}} into the open object of `json` (an empty object
/// when no component recorded a stage).
void write_timing_section(JsonWriter& json, const RunFigures& figures);

}  // namespace robodds::evaluator
