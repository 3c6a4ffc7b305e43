#pragma once
// Every parameter of the truth_estimator component. The table is the one source of the keys,
// defaults (the member initialisers), units, ranges and descriptions;
// config/truth_estimator.params.yaml is generated from it.

#include <cstdint>
#include <string>
#include <vector>

#include "common/param_table.hpp"

namespace robodds::truth_estimator {

struct TruthEstimatorParams {
  double rate_hz = 100.0;
  std::int64_t inject_nan_at_step = -1;
};

const params::ParamTable<TruthEstimatorParams>& truth_estimator_param_table();

}  // namespace robodds::truth_estimator
