#pragma once
// Every parameter of the pf_estimator component: the filter's (PfParams) plus the node's own.
// The table is the one source of the keys, defaults and documentation
// (config/pf_estimator.params.yaml is generated from it).

#include "common/param_table.hpp"
#include "components/pf_estimator/pf_params.hpp"

namespace robodds::pf {

struct PfEstimatorNodeParams {
  double rate_hz = 100.0;  // Hz, estimate publication rate
  PfParams filter;
  double valid_max_position_std_m = 3.0;  // m, threshold of the estimate's valid flag
};

const params::ParamTable<PfEstimatorNodeParams>& pf_estimator_param_table();

}  // namespace robodds::pf
