#pragma once
// The main of a component executable robodds-<type>: the generic host with that one component,
// for a robot without a scenario file. CMake generates one tiny main per component type
// (robodds_component() in cmake/RoboddsHelpers.cmake) that calls this with the type's
// registration function.

#include "runtime/component/registry.hpp"

namespace robodds {

/// Parses the component options (runtime/launch/host_args.hpp add_component_options: --robot, --name,
/// --params, --step, --realtime, DDS and lockstep options ...; --help lists the component's
/// parameters too) and runs the component until the run ends (lockstep: the coordinator's
/// final tick) or a signal stops it. Returns the exit code (0, 1, 2, 130/143 as for robodds).
int component_main(int argc, char** argv, const char* type, void (*register_type)(ComponentRegistry&));

}  // namespace robodds
