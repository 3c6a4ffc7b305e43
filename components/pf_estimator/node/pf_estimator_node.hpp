#pragma once
#include <memory>

#include "common/param_doc.hpp"
#include "runtime/component.hpp"

namespace robodds::pf {
/// sensor/odometry + sensor/position in, estimate/pose out (one particle filter per robot).
std::unique_ptr<Component> make_pf_estimator_node();
/// Its parameters (keys, types, defaults, units, ranges, descriptions).
params::ParamDoc pf_estimator_params_doc();
}  // namespace robodds::pf
