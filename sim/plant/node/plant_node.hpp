#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::plant {
/// DDS node of the differential-drive plant: plant/cmd in, plant/state out.
std::unique_ptr<Component> make_plant_node();
}  // namespace robodds::plant
