#include "components/range_rate_observer/node/range_rate_observer_params.hpp"

namespace robodds::range_rate_observer {

const params::ParamTable<ObserverNodeParams>& observer_node_param_table() {
  using P = ObserverNodeParams;
  static const params::ParamTable<P> table =
      params::ParamTable<P>(
          "Range-rate observers on each robot's range stream: paper 2's super-twisting observer (eq. 1) on\n"
          "observer/range_rate, its linear baseline (eq. 9) on observer/range_rate_linear and a Kalman filter\n"
          "on range, rate and range acceleration (issue 28) on observer/range_rate_kf, all fed the same\n"
          "samples; restarted on a range jump and on a target change.")
          .add("rate_hz", &P::rate_hz, "Hz", params::positive(), "publication rate; the range sensor's rate")
          .include_as("sta", &P::sta, super_twisting_param_table(), "super-twisting observer, eq. (1) (observer/range_rate)")
          .include_as("linear", &P::linear, linear_observer_param_table(),
                      "linear baseline observer, eq. (9) (observer/range_rate_linear)")
          .include_as("kalman", &P::kalman, kalman_observer_param_table(),
                      "Kalman filter on range, rate and range acceleration (observer/range_rate_kf, issue 28)")
          .include_as("uncertainty", &P::uncertainty, rate_uncertainty_param_table(),
                      "the range_rate_std_mps every observer reports (issue 27)");
  return table;
}

void ObserverNodeParams::validate() const { observer_node_param_table().check_ranges(*this); }

}  // namespace robodds::range_rate_observer
