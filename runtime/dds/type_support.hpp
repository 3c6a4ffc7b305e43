#pragma once
// Fast DDS type support by registered type name (runtime-internal; includes Fast DDS).

#include <fastdds/dds/topic/TopicDataType.hpp>

#include <string>

namespace robodds {

/// A new TopicDataType for `type_name` (e.g. "robodds::idl::SimTick") announcing no
/// TypeObject/TypeInformation (XCDR1 interop with other vendors), or nullptr if unknown.
/// A payload it cannot decode is dropped (deserialize() false), never thrown; `count_undecodable`:
/// also counted (undecodable_samples()) and logged once per type, as a received sample is. A
/// writer decoding its own payload (RawPayloadType::getKey) counts nothing.
eprosima::fastdds::dds::TopicDataType* make_type_support(const std::string& type_name, bool count_undecodable = true);

}  // namespace robodds
