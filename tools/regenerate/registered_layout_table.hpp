#pragma once
// README.md's generated layout rows of what this build registers (layout_table.hpp renders them).

#include <string>

namespace robodds {

/// render_layout_table() of every component type built with robodds_component() and every
/// metrics module built with robodds_metrics_module().
std::string render_registered_layout_table();

}  // namespace robodds
