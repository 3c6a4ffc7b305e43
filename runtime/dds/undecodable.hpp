#pragma once
// Samples the DDS type support could not decode (Fast-DDS-free header). Fast DDS 2.9 drops such
// a sample without any status or counter (docs/interop.md, "Hostile input"); the runtime's type
// support counts them per type name and logs the first one of each type.

#include <cstdint>
#include <string>

namespace robodds {

/// Undecodable samples of `type_name` (e.g. "robodds::idl::StepDone") received by this
/// process so far; they never reach an Input.
std::uint64_t undecodable_samples(const std::string& type_name);

}  // namespace robodds
