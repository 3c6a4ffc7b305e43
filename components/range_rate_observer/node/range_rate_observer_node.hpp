#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::range_rate_observer {
/// sensor/range in (per robot, whatever its target), observer/range_rate (super-twisting) and
/// observer/range_rate_linear (linear baseline) out, keyed (robot, target), at rate_hz.
std::unique_ptr<Component> make_range_rate_observer_node();
}  // namespace robodds::range_rate_observer
