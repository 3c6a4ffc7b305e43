#include "components/range_rate_observer/node/scenario_observer_bound.hpp"

#include "components/range_rate_observer/observer_params.hpp"
#include "runtime/params.hpp"

namespace robodds::range_rate {

std::optional<ScenarioObserverBound> scenario_observer_bound(const Scenario& scenario) {
  for (const ComponentSpec& spec : scenario.components) {
    if (spec.type != "range_rate_observer") {
      continue;
    }
    ParamReader overrides(spec.name, spec.overrides);
    if (overrides.has("sta.b")) {
      return ScenarioObserverBound{overrides.get_double("sta.b"), spec.name + ".sta.b", false};
    }
    return ScenarioObserverBound{SuperTwistingParams{}.b, spec.name + ".sta.b (default)", true};
  }
  return std::nullopt;
}

}  // namespace robodds::range_rate
