#pragma once
// The instance key of a sample the runtime only sees as `const void*` (a bus's writer): the same
// 64-bit key inputs use (idl::instance_key, e.g. the robot id), chosen by the IDL type name.

#include <cstdint>
#include <string>

namespace robodds {

using SampleKeyFunction = std::uint64_t (*)(const void* sample);

/// idl::instance_key of the type named `type_name` (e.g. "robodds::idl::SimTick"), or nullptr
/// when no IDL type has that name.
SampleKeyFunction sample_key_function(const std::string& type_name);

}  // namespace robodds
