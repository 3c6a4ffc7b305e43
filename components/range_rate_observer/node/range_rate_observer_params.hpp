#pragma once
// Every parameter of the range_rate_observer component: its rate and the gains of both observers
// (config/range_rate_observer.params.yaml is generated from the table).

#include "common/param_table.hpp"
#include "components/range_rate_observer/observer_params.hpp"
#include "components/range_rate_observer/rate_uncertainty.hpp"

namespace robodds::range_rate_observer {

/// The node's defaults of the uncertainty keys: the library's, but initial_rate_std_mps 0 (the
/// robot's top speed / 3, from the scenario's robot_body fact).
inline RateUncertaintyParams node_uncertainty_defaults() {
  RateUncertaintyParams u;
  u.initial_rate_std_mps = 0.0;
  return u;
}

// Units, ranges and descriptions: observer_node_param_table() (the one source). Defaults: the
// member initialisers here and in observer_params.hpp.
struct ObserverNodeParams {
  double rate_hz = 50.0;
  SuperTwistingParams sta;       // keys sta.*
  LinearObserverParams linear;   // keys linear.*
  KalmanObserverParams kalman;   // keys kalman.* (issue 28)
  RateUncertaintyParams uncertainty = node_uncertainty_defaults();  // keys uncertainty.* (every observer's reported rate std)

  /// Throws std::invalid_argument "key: reason (got value)" for the first bad field.
  void validate() const;
};

const params::ParamTable<ObserverNodeParams>& observer_node_param_table();

}  // namespace robodds::range_rate_observer
