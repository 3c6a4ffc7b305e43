#include "runtime/dds/discovery.hpp"
#include "runtime/dds/participant.hpp"
#include "runtime/dds/qos_files.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>

#include <algorithm>
#include <chrono>
#include <iterator>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <set>
#include <thread>

#include "runtime/base/error.hpp"
#include "runtime/dds/text.hpp"

namespace robodds {
namespace dds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;

namespace {

std::string qos_text(bool reliable, bool transient_local) {
  return std::string(reliable ? "RELIABLE" : "BEST_EFFORT") + "/" + (transient_local ? "TRANSIENT_LOCAL" : "VOLATILE");
}

std::optional<double> finite_seconds(const eprosima::fastrtps::Duration_t& d) {
  if (d == eprosima::fastrtps::c_TimeInfinite) {
    return std::nullopt;
  }
  return d.seconds + d.nanosec / 1e9;  // not to_ns() * 1e-9: 0.3 s must not print as 0.30000000000000004
}

const char* durability_text(dds::DurabilityQosPolicyKind kind) {
  switch (kind) {
    case dds::VOLATILE_DURABILITY_QOS: return "VOLATILE";
    case dds::TRANSIENT_LOCAL_DURABILITY_QOS: return "TRANSIENT_LOCAL";
    case dds::TRANSIENT_DURABILITY_QOS: return "TRANSIENT";
    case dds::PERSISTENT_DURABILITY_QOS: return "PERSISTENT";
  }
  return "?";
}

const char* liveliness_text(dds::LivelinessQosPolicyKind kind) {
  switch (kind) {
    case dds::AUTOMATIC_LIVELINESS_QOS: return "AUTOMATIC";
    case dds::MANUAL_BY_PARTICIPANT_LIVELINESS_QOS: return "MANUAL_BY_PARTICIPANT";
    case dds::MANUAL_BY_TOPIC_LIVELINESS_QOS: return "MANUAL_BY_TOPIC";
  }
  return "?";
}

/// The announced QoS of a writer (WriterQos) or a reader (ReaderQos): the same policies by the same names.
template <class Q>
EndpointQos endpoint_qos(const Q& q) {
  EndpointQos out;
  out.reliability = q.m_reliability.kind == dds::RELIABLE_RELIABILITY_QOS ? "RELIABLE" : "BEST_EFFORT";
  out.durability = durability_text(q.m_durability.kind);
  out.deadline_s = finite_seconds(q.m_deadline.period);
  out.lifespan_s = finite_seconds(q.m_lifespan.duration);
  out.liveliness = liveliness_text(q.m_liveliness.kind);
  out.liveliness_lease_s = finite_seconds(q.m_liveliness.lease_duration);
  out.ownership = q.m_ownership.kind == dds::EXCLUSIVE_OWNERSHIP_QOS ? "EXCLUSIVE" : "SHARED";
  return out;
}

std::string guid_text(const rtps::GUID_t& guid) {
  std::ostringstream out;
  out << guid;
  return out.str();
}

/// The host a participant announced: Fast DDS's physical data property ("HOST:DOMAIN"), which a
/// Fast DDS built with statistics (as Debian's 2.9.1 is) announces for every participant, also one
/// made from an XML profile; empty when it announced none (another build, another vendor).
std::string announced_host(const rtps::ParticipantProxyData& data) {
  for (const auto& property : data.m_properties) {
    if (property.first() == dds::parameter_policy_physical_data_host) {
      const std::string value = property.second();
      return value.substr(0, value.rfind(':'));  // the domain id Fast DDS appends is not part of the host
    }
  }
  return "";
}

class DiscoveryListener : public dds::DomainParticipantListener {
 public:
  void on_participant_discovery(dds::DomainParticipant*, rtps::ParticipantDiscoveryInfo&& info) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string prefix = guid_prefix_text(info.info.m_guid.guidPrefix);
    if (info.status == rtps::ParticipantDiscoveryInfo::REMOVED_PARTICIPANT ||
        info.status == rtps::ParticipantDiscoveryInfo::DROPPED_PARTICIPANT) {
      // Its endpoints went with it, whether or not their own removal was reported.
      for (auto it = endpoints_.begin(); it != endpoints_.end();) {
        it = it->second.prefix == prefix ? endpoints_.erase(it) : std::next(it);
      }
      return;
    }
    participant_names_[prefix] = info.info.m_participantName.to_string();
    hosts_[prefix] = announced_host(info.info);
  }
  void on_publisher_discovery(dds::DomainParticipant*, rtps::WriterDiscoveryInfo&& info) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string guid = guid_text(info.info.guid());
    if (info.status == rtps::WriterDiscoveryInfo::REMOVED_WRITER) {
      endpoints_.erase(guid);
      return;
    }
    DiscoveredTopic& t = entry(info.info.topicName().to_string(), info.info.typeName().to_string());
    writer_prefixes_[t.name].insert(guid_prefix_text(info.info.guid().guidPrefix));
    if (t.writer_qos.empty()) {
      t.writer_qos = qos_text(info.info.m_qos.m_reliability.kind == dds::RELIABLE_RELIABILITY_QOS,
                              info.info.m_qos.m_durability.kind == dds::TRANSIENT_LOCAL_DURABILITY_QOS);
    }
    Endpoint& e = endpoints_[guid];
    e.topic = t.name;
    e.prefix = guid_prefix_text(info.info.guid().guidPrefix);
    e.data.writer = true;
    e.data.guid = guid;
    e.data.qos = endpoint_qos(info.info.m_qos);
    if (info.info.m_qos.m_ownership.kind == dds::EXCLUSIVE_OWNERSHIP_QOS) {
      e.data.qos.ownership_strength = info.info.m_qos.m_ownershipStrength.value;
    }
  }
  void on_subscriber_discovery(dds::DomainParticipant*, rtps::ReaderDiscoveryInfo&& info) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string guid = guid_text(info.info.guid());
    if (info.status == rtps::ReaderDiscoveryInfo::REMOVED_READER) {
      endpoints_.erase(guid);
      return;
    }
    DiscoveredTopic& t = entry(info.info.topicName().to_string(), info.info.typeName().to_string());
    if (t.reader_qos.empty()) {
      t.reader_qos = qos_text(info.info.m_qos.m_reliability.kind == dds::RELIABLE_RELIABILITY_QOS,
                              info.info.m_qos.m_durability.kind == dds::TRANSIENT_LOCAL_DURABILITY_QOS);
    }
    Endpoint& e = endpoints_[guid];
    e.topic = t.name;
    e.prefix = guid_prefix_text(info.info.guid().guidPrefix);
    e.data.writer = false;
    e.data.guid = guid;
    e.data.qos = endpoint_qos(info.info.m_qos);
  }
  std::vector<DiscoveredTopic> topics() {
    std::lock_guard<std::mutex> lock(mutex_);
    // Named at the end: a participant's name may arrive after its first endpoints.
    const auto name_of = [this](const std::string& prefix) {
      const auto it = participant_names_.find(prefix);
      return it == participant_names_.end() || it->second.empty() ? prefix : it->second;
    };
    for (auto& [guid, e] : endpoints_) {
      e.data.participant = name_of(e.prefix);
      const auto host = hosts_.find(e.prefix);
      e.data.host = host == hosts_.end() ? "" : host->second;
    }
    std::vector<DiscoveredTopic> out;
    for (auto& [name, t] : topics_) {
      out.push_back(t);
      DiscoveredTopic& o = out.back();
      std::set<std::string> participants;
      for (const std::string& prefix : writer_prefixes_[name]) {
        participants.insert(name_of(prefix));
      }
      o.writer_participants.assign(participants.begin(), participants.end());
      for (const auto& [guid, e] : endpoints_) {
        if (e.topic == name) {
          o.endpoints.push_back(e.data);
        }
      }
      std::stable_sort(o.endpoints.begin(), o.endpoints.end(), [](const DiscoveredEndpoint& a, const DiscoveredEndpoint& b) {
        return a.writer != b.writer ? a.writer : a.participant < b.participant;
      });
      o.writers = static_cast<int>(std::count_if(o.endpoints.begin(), o.endpoints.end(), [](const DiscoveredEndpoint& e) { return e.writer; }));
      o.readers = static_cast<int>(o.endpoints.size()) - o.writers;
    }
    return out;
  }

 private:
  struct Endpoint {
    std::string topic;
    std::string prefix;  // its participant's GUID prefix
    DiscoveredEndpoint data;
  };
  DiscoveredTopic& entry(const std::string& name, const std::string& type) {
    DiscoveredTopic& t = topics_[name];
    t.name = name;
    t.type_name = type;
    return t;
  }
  std::mutex mutex_;
  std::map<std::string, DiscoveredTopic> topics_;
  std::map<std::string, std::set<std::string>> writer_prefixes_;  // topic -> GUID prefixes of its writers
  std::map<std::string, std::string> participant_names_;          // GUID prefix -> name
  std::map<std::string, std::string> hosts_;                      // GUID prefix -> announced host
  std::map<std::string, Endpoint> endpoints_;                     // endpoint GUID -> endpoint, while not removed
};

}  // namespace

std::vector<DiscoveredTopic> discover_topics(const DdsOptions& options, double seconds) {
  dds::DomainParticipantQos qos = checked_participant_qos(options);
  qos.name("robodds-topics");
  // A Discovery Server passes a CLIENT only the endpoints of the topics it has endpoints on
  // itself (none here): a SUPER_CLIENT gets every participant's and endpoint's discovery data
  // (as the ros2 daemon does), so `robodds topics`/`info` see a server-discovered system too.
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  if (discovery.discoveryProtocol == rtps::DiscoveryProtocol_t::CLIENT) {
    discovery.discoveryProtocol = rtps::DiscoveryProtocol_t::SUPER_CLIENT;
  }
  DiscoveryListener listener;  // declared before the participant: outlives it
  // Only discovery callbacks: leave data_on_readers out of the mask (it would swallow data).
  ParticipantPtr participant =
      create_participant(options.domain_id, qos, &listener, dds::StatusMask::none(), options.participant_profile);
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  participant.reset();  // no callback runs once it returns
  return listener.topics();
}

}  // namespace robodds
