#pragma once
#include <memory>

#include "common/param_doc.hpp"
#include "runtime/component.hpp"

namespace robodds::truth_estimator {
/// plant/state in, estimate/pose out (the true pose, zero covariance, valid).
std::unique_ptr<Component> make_truth_estimator_node();
/// Its parameters (keys, types, defaults, units, ranges, descriptions).
params::ParamDoc truth_estimator_params_doc();
}  // namespace robodds::truth_estimator
