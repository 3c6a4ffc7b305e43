#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::target_mission {
/// Paper 2's mission: publishes every served robot's task (common/model/target_plan.hpp) from the
/// scenario's `targets:` and `events:` on mission/target, at step 0 and again at each event step,
/// each sample saying when the next comes (next_step: the next event step, or never).
std::unique_ptr<Component> make_target_mission_node();
}  // namespace robodds::target_mission
