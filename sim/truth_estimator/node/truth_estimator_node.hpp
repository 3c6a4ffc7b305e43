#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::truth_estimator {
/// plant/state in, estimate/pose out (the true pose, zero covariance, valid).
std::unique_ptr<Component> make_truth_estimator_node();
}  // namespace robodds::truth_estimator
