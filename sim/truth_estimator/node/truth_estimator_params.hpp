#pragma once
// Every parameter of the truth_estimator component.
// config/truth_estimator.params.yaml is generated from the table.

#include <cstdint>
#include <string>
#include <vector>

#include "common/param_table.hpp"

namespace robodds::truth_estimator {

// Units, ranges and one-line descriptions of these fields: truth_estimator_param_table() in
// truth_estimator_params.cpp (the one source; `robodds components --params truth_estimator` prints
// it). Defaults: the member initialisers.
struct TruthEstimatorParams {
  double rate_hz = 100.0;
  std::int64_t inject_nan_at_step = -1;
};

const params::ParamTable<TruthEstimatorParams>& truth_estimator_param_table();

}  // namespace robodds::truth_estimator
