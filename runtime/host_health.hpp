#pragma once
// What one host reports about its run for summary.json's "hosts" and "inputs" sections: its
// real-time overrun figures, the samples its DDS type support could not decode (per topic) and,
// per component, what each input did with its samples. The evaluator's host has its own; across
// processes the others arrive on `run/health`.

#include <map>
#include <string>
#include <vector>

#include "runtime/io.hpp"
#include "runtime/overrun_counter.hpp"

namespace robodds {

struct InputHealth {
  std::string topic;
  InputCounts counts;
};

struct ComponentHealth {
  std::string component;
  std::vector<InputHealth> inputs;
};

struct HostHealth {
  std::string member;        // the host's group (its name in acknowledgements)
  OverrunFigures figures;    // ticks; in lockstep no step is ever missed or late
  std::vector<ComponentHealth> components;
  std::map<std::string, std::uint64_t> undecodable;  // topic -> samples dropped undecoded (Bus::undecodable_samples)
};

/// The counts of every input in `inputs` (ComponentContext::inputs()), in subscription order.
ComponentHealth component_health(const std::string& component, const std::vector<std::unique_ptr<InputBase>>& inputs);

}  // namespace robodds
