#pragma once
// Every parameter of the pf_estimator component: the filter's (PfParams) plus the node's own.
// config/pf_estimator.params.yaml is generated from the table.

#include "common/param_table.hpp"
#include "components/pf_estimator/pf_params.hpp"

namespace robodds::pf_estimator {

// Units, ranges and one-line descriptions of these fields: pf_estimator_param_table() in
// pf_estimator_params.cpp (the one source; `robodds components --params pf_estimator` prints it).
// Defaults: the member initialisers.
struct PfEstimatorNodeParams {
  double rate_hz = 100.0;
  PfParams filter;
  double valid_max_position_std_m = 3.0;
  double valid_max_heading_std_rad = 0.2;
  double valid_keep_max_heading_std_rad = 0.35;
  double input_timeout_s = 0.5;
  bool extrapolate_to_step = true;

  /// The table's ranges, then valid_keep_max_heading_std_rad >= valid_max_heading_std_rad.
  void validate() const;
};

const params::ParamTable<PfEstimatorNodeParams>& pf_estimator_param_table();

}  // namespace robodds::pf_estimator
