#pragma once
#include <memory>

#include "runtime/component.hpp"

namespace robodds::evaluator {
/// Records topics to CSV and writes summary.json (metrics) and summary.txt at the end.
std::unique_ptr<Component> make_evaluator_node();
}  // namespace robodds::evaluator
