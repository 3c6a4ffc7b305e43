#pragma once
// The super-twisting gain b of a scenario's range_rate_observer: the bound on the range
// acceleration the observer follows exactly. The guidance controller checks its limits against
// it at start-up and the evaluator counts the samples above it; both read it here.

#include <optional>
#include <string>

#include "runtime/scenario.hpp"

namespace robodds::range_rate {

struct ScenarioObserverBound {
  double b_mps2 = 0.0;  // m/s^2
  std::string key;      // where it comes from: "<component>.sta.b", or "<component>.sta.b (default)"
  bool is_default = false;  // the scenario does not set it: the observer's own default
};

/// b of the first range_rate_observer component of `scenario` (its `sta.b` override, else
/// SuperTwistingParams' default); nullopt when the scenario has none (the observer runs
/// elsewhere, or a test feeds its topic).
std::optional<ScenarioObserverBound> scenario_observer_bound(const Scenario& scenario);

}  // namespace robodds::range_rate
