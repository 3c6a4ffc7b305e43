// Compiled into every program that links robodds_system (system/CMakeLists.txt adds it to their
// sources, not to a library: a static library's unreferenced object would be dropped by the
// linker, and with it this initialiser). It installs the robot system's topics and sample checks
// in the runtime before main(), so no run, tool or test can start without them.
#include "system/topics.hpp"

namespace {
const bool kRobotSystemInstalled = (robodds::system::install_robot_system(), true);
}  // namespace
