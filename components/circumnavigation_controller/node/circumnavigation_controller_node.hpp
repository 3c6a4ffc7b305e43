#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::circumnavigation_controller {
/// observer/range_rate (or _linear) + mission/target + estimate/pose (all robots) in; plant/cmd out.
std::unique_ptr<Component> make_circumnavigation_controller_node();
}  // namespace robodds::circumnavigation_controller
