#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::evaluator {
/// Records topics to CSV as samples arrive and writes summary.json (status and metrics) at the
/// end of the run or when it fails.
std::unique_ptr<Component> make_evaluator_node();
}  // namespace robodds::evaluator
