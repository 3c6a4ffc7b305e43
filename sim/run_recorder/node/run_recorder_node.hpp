#pragma once
#include <memory>

#include "runtime/component/component.hpp"

namespace robodds::run_recorder {
/// Records the scenario's published topics into an MCAP file (run_recorder_params.hpp).
std::unique_ptr<Component> make_run_recorder_node();
}  // namespace robodds::run_recorder
