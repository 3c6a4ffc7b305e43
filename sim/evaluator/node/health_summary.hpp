#pragma once
// summary.json's "hosts" and "inputs" sections: what every host of the run reported about
// itself (RunFigures::hosts): real-time overruns and, per component and input topic, the samples
// accepted, rejected and adjusted per reason. Kept apart from "metrics" (they depend on the
// deployment and, in real time, on the machine).

#include "common/json_writer.hpp"
#include "runtime/component/component.hpp"

namespace robodds::evaluator {

/// Writes "hosts" ({member: {ticks, missed_steps, late_steps, worst_lateness_s, undecodable:
/// {topic: samples dropped undecoded}}}, plus
/// {"reported": false} for each member not heard from) and "inputs" ({component: {topic:
/// {accepted, rejected: {reason: n}, adjusted: {reason: n}}}}) into the open object of `json`.
void write_health_sections(JsonWriter& json, const RunFigures& figures);

}  // namespace robodds::evaluator
