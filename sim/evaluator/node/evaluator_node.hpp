#pragma once
#include <memory>

#include "common/param_doc.hpp"
#include "runtime/component.hpp"

namespace robodds::evaluator {
/// Records topics to CSV and writes summary.json (metrics) and summary.txt at the end.
std::unique_ptr<Component> make_evaluator_node();
/// Its parameters (keys, types, defaults, units, ranges, descriptions).
params::ParamDoc evaluator_params_doc();
}  // namespace robodds::evaluator
