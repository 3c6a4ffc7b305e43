#pragma once
// How DDS QoS policies and GUIDs are written in log lines and error messages (runtime-internal;
// includes Fast DDS).

#include <fastdds/dds/core/policy/QosPolicies.hpp>
#include <fastdds/rtps/common/GuidPrefix_t.hpp>

#include <string>

namespace robodds {

/// "RELIABILITY", "DURABILITY", ... or "policy <id>" for one this runtime does not name.
std::string policy_name(eprosima::fastdds::dds::QosPolicyId_t id);

/// The policies that decide writer/reader compatibility, in one short text for error messages,
/// e.g. "RELIABLE/TRANSIENT_LOCAL" or "RELIABLE/VOLATILE/deadline 300 ms/liveliness MANUAL_BY_TOPIC 1000 ms".
std::string describe_qos(const eprosima::fastdds::dds::ReliabilityQosPolicy& reliability,
                         const eprosima::fastdds::dds::DurabilityQosPolicy& durability,
                         const eprosima::fastdds::dds::DeadlineQosPolicy& deadline,
                         const eprosima::fastdds::dds::LivelinessQosPolicy& liveliness);

/// Fast DDS's text for a GUID prefix (e.g. "01.0f.2d.41.a4.7e.5b.5c.01.00.00.00"): names a participant
/// whose name is not known yet, and keys the tables of what discovery reported per participant.
std::string guid_prefix_text(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix);

}  // namespace robodds
