#include "runtime/dds/text.hpp"

#include <sstream>

namespace robodds {
namespace dds = eprosima::fastdds::dds;

namespace {

std::string ms_text(const eprosima::fastrtps::Duration_t& d) { return std::to_string(d.to_ns() / 1000000) + " ms"; }

}  // namespace

std::string policy_name(dds::QosPolicyId_t id) {
  switch (id) {
    case dds::DURABILITY_QOS_POLICY_ID: return "DURABILITY";
    case dds::DEADLINE_QOS_POLICY_ID: return "DEADLINE";
    case dds::LIVELINESS_QOS_POLICY_ID: return "LIVELINESS";
    case dds::RELIABILITY_QOS_POLICY_ID: return "RELIABILITY";
    case dds::OWNERSHIP_QOS_POLICY_ID: return "OWNERSHIP";
    case dds::DESTINATIONORDER_QOS_POLICY_ID: return "DESTINATION_ORDER";
    case dds::PRESENTATION_QOS_POLICY_ID: return "PRESENTATION";
    case dds::PARTITION_QOS_POLICY_ID: return "PARTITION";
    case dds::DATAREPRESENTATION_QOS_POLICY_ID: return "DATA_REPRESENTATION";
    default: return "policy " + std::to_string(static_cast<int>(id));
  }
}

std::string describe_qos(const dds::ReliabilityQosPolicy& r, const dds::DurabilityQosPolicy& d,
                         const dds::DeadlineQosPolicy& dl, const dds::LivelinessQosPolicy& l) {
  std::string out = r.kind == dds::RELIABLE_RELIABILITY_QOS ? "RELIABLE" : "BEST_EFFORT";
  out += d.kind == dds::TRANSIENT_LOCAL_DURABILITY_QOS ? "/TRANSIENT_LOCAL" : (d.kind == dds::VOLATILE_DURABILITY_QOS ? "/VOLATILE" : "/other");
  if (dl.period != eprosima::fastrtps::c_TimeInfinite) {
    out += "/deadline " + ms_text(dl.period);
  }
  if (l.lease_duration != eprosima::fastrtps::c_TimeInfinite) {
    const char* kind = l.kind == dds::AUTOMATIC_LIVELINESS_QOS               ? "AUTOMATIC"
                       : l.kind == dds::MANUAL_BY_PARTICIPANT_LIVELINESS_QOS ? "MANUAL_BY_PARTICIPANT"
                                                                             : "MANUAL_BY_TOPIC";
    out += std::string("/liveliness ") + kind + " " + ms_text(l.lease_duration);
  }
  return out;
}

std::string guid_prefix_text(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) {
  std::ostringstream out;
  out << prefix;
  return out.str();
}

}  // namespace robodds
