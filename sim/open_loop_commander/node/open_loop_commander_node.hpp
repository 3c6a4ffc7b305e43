#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::open_loop_commander {
/// Publishes open-loop plant/cmd for every robot it serves.
std::unique_ptr<Component> make_open_loop_node();
}  // namespace robodds::open_loop_commander
