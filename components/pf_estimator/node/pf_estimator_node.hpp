#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::pf_estimator {
/// sensor/odometry + sensor/position in, estimate/pose out (one particle filter per robot).
std::unique_ptr<Component> make_pf_estimator_node();
}  // namespace robodds::pf_estimator
