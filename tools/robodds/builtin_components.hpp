#pragma once
#include "runtime/registry.hpp"

namespace robodds {
/// Registers every component type shipped with robodds.
void register_builtin_components(ComponentRegistry& registry);
}  // namespace robodds
