#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::replay_source {
/// Publishes topics of a recording into a lockstep run: each sample at the step its header names.
std::unique_ptr<Component> make_replay_source_node();
}  // namespace robodds::replay_source
