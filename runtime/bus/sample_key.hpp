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

/// A sample's header steps: SampleHeader::step and ::next_step (the step of its instance's next sample).
struct SampleSteps {
  std::uint64_t step = 0;
  std::uint64_t next_step = 0;
};
using SampleStepsFunction = SampleSteps (*)(const void* sample);

/// The header steps of a sample of the type named `type_name`, or nullptr when no IDL type has that name.
SampleStepsFunction sample_steps_function(const std::string& type_name);

}  // namespace robodds
