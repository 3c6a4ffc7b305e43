#pragma once
#include <memory>

#include "common/param_doc.hpp"
#include "runtime/component.hpp"

namespace robodds::open_loop {
/// Publishes open-loop plant/cmd for every robot it serves.
std::unique_ptr<Component> make_open_loop_node();
/// Its parameters (keys, types, defaults, units, ranges, descriptions).
params::ParamDoc open_loop_commander_params_doc();
}  // namespace robodds::open_loop
