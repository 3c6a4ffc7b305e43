#pragma once
// Every parameter of the evaluator component.
// config/evaluator.params.yaml is generated from the table.

#include <cstdint>
#include <string>
#include <vector>

#include "common/param_table.hpp"

namespace robodds::evaluator {

// Units, ranges and one-line descriptions of these fields: evaluator_param_table() in
// evaluator_params.cpp (the one source; `robodds components --params evaluator` prints it).
// Defaults: the member initialisers.
struct EvaluatorParams {
  std::vector<std::string> topics{"plant/state", "plant/cmd", "sensor/position"};
  double metrics_after_s = 5.0;
};

const params::ParamTable<EvaluatorParams>& evaluator_param_table();

}  // namespace robodds::evaluator
