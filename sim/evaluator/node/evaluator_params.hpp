#pragma once
// Every parameter of the evaluator component. The table is the one source of the keys,
// defaults (the member initialisers), units, ranges and descriptions;
// config/evaluator.params.yaml is generated from it.

#include <cstdint>
#include <string>
#include <vector>

#include "common/param_table.hpp"

namespace robodds::evaluator {

struct EvaluatorParams {
  std::vector<std::string> topics{"plant/state", "plant/cmd", "sensor/position"};
  double metrics_after_s = 5.0;
};

const params::ParamTable<EvaluatorParams>& evaluator_param_table();

}  // namespace robodds::evaluator
