#pragma once
// What one host reports about its run for summary.json's "hosts", "inputs" and run.timing: its
// real-time overrun figures, the samples its DDS type support could not decode (per topic), per
// component what each input did with its samples and its compute times per stage. The
// evaluator's host has its own; across processes the others arrive on `run/health`.

#include <map>
#include <string>
#include <vector>

#include "runtime/health/compute_times.hpp"
#include "runtime/io/io.hpp"
#include "runtime/health/overrun_counter.hpp"

namespace robodds {

struct InputHealth {
  std::string topic;
  InputCounts counts;
};

struct ComponentHealth {
  std::string component;
  std::vector<InputHealth> inputs;
};

/// One stage of one component's compute times (ComponentContext::compute_times()).
struct StageTiming {
  std::string component;
  ComputeTimes::Summary times;
};

struct HostHealth {
  std::string member;        // the host's group (its name in acknowledgements)
  OverrunFigures figures;    // ticks; in lockstep no step is ever missed or late
  std::vector<ComponentHealth> components;
  std::map<std::string, std::uint64_t> undecodable;  // topic -> samples dropped undecoded (Bus::undecodable_samples)
  std::vector<StageTiming> timing;   // per component (host order), its stages in first-added order
  std::string degraded;              // real time: why the host ran degraded (PeerWatch); empty: it did not
};

/// The counts of every input in `inputs` (ComponentContext::inputs()), in subscription order.
ComponentHealth component_health(const std::string& component, const std::vector<std::unique_ptr<InputBase>>& inputs);

/// Appends the stage summaries of `component`'s `times` to `timing`.
void add_stage_timing(std::vector<StageTiming>& timing, const std::string& component, const ComputeTimes& times);

}  // namespace robodds
