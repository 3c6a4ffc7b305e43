#include "sim/truth_estimator/node/truth_estimator_params.hpp"

#include "sim/truth_estimator/node/truth_estimator_node.hpp"

namespace robodds::truth_estimator {

const params::ParamTable<TruthEstimatorParams>& truth_estimator_param_table() {
  static const params::ParamTable<TruthEstimatorParams> table =
      params::ParamTable<TruthEstimatorParams>(
          "Publishes the true pose as the pose estimate (zero covariance, always valid): the \"ideal\"\n"
          "setting of paper 1's Table 1, where the controller is fed the true pose.")
          .add("rate_hz", &TruthEstimatorParams::rate_hz, "Hz", params::positive(), "must divide the simulation rate")
          .add("inject_nan_at_step", &TruthEstimatorParams::inject_nan_at_step, "", params::any<long long>(),
               "step at which x is published as NaN (fault injection for tests); -1 = never");
  return table;
}

}  // namespace robodds::truth_estimator
