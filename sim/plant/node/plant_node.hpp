#pragma once
#include <memory>

#include "common/param_doc.hpp"
#include "runtime/component.hpp"

namespace robodds::plant {
/// DDS node of the differential-drive plant: plant/cmd in, plant/state out.
std::unique_ptr<Component> make_plant_node();
/// Its parameters (keys, types, defaults, units, ranges, descriptions).
params::ParamDoc plant_params_doc();
}  // namespace robodds::plant
