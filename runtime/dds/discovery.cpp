#include "runtime/dds/discovery.hpp"
#include "runtime/dds/participant.hpp"
#include "runtime/dds/qos_files.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>

#include <chrono>
#include <map>
#include <mutex>
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

class DiscoveryListener : public dds::DomainParticipantListener {
 public:
  void on_participant_discovery(dds::DomainParticipant*, rtps::ParticipantDiscoveryInfo&& info) override {
    if (info.status != rtps::ParticipantDiscoveryInfo::DISCOVERED_PARTICIPANT) {
      return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    participant_names_[guid_prefix_text(info.info.m_guid.guidPrefix)] = info.info.m_participantName.to_string();
  }
  void on_publisher_discovery(dds::DomainParticipant*, rtps::WriterDiscoveryInfo&& info) override {
    if (info.status != rtps::WriterDiscoveryInfo::DISCOVERED_WRITER) {
      return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    DiscoveredTopic& t = entry(info.info.topicName().to_string(), info.info.typeName().to_string());
    ++t.writers;
    writer_prefixes_[t.name].insert(guid_prefix_text(info.info.guid().guidPrefix));
    if (t.writer_qos.empty()) {
      t.writer_qos = qos_text(info.info.m_qos.m_reliability.kind == dds::RELIABLE_RELIABILITY_QOS,
                              info.info.m_qos.m_durability.kind == dds::TRANSIENT_LOCAL_DURABILITY_QOS);
    }
  }
  void on_subscriber_discovery(dds::DomainParticipant*, rtps::ReaderDiscoveryInfo&& info) override {
    if (info.status != rtps::ReaderDiscoveryInfo::DISCOVERED_READER) {
      return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    DiscoveredTopic& t = entry(info.info.topicName().to_string(), info.info.typeName().to_string());
    ++t.readers;
    if (t.reader_qos.empty()) {
      t.reader_qos = qos_text(info.info.m_qos.m_reliability.kind == dds::RELIABLE_RELIABILITY_QOS,
                              info.info.m_qos.m_durability.kind == dds::TRANSIENT_LOCAL_DURABILITY_QOS);
    }
  }
  std::vector<DiscoveredTopic> topics() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<DiscoveredTopic> out;
    for (auto& [name, t] : topics_) {
      out.push_back(t);
      // Named at the end: a participant's name may arrive after its first endpoints.
      std::set<std::string> participants;
      for (const std::string& prefix : writer_prefixes_[name]) {
        const auto it = participant_names_.find(prefix);
        participants.insert(it == participant_names_.end() || it->second.empty() ? prefix : it->second);
      }
      out.back().writer_participants.assign(participants.begin(), participants.end());
    }
    return out;
  }

 private:
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
};

}  // namespace

std::vector<DiscoveredTopic> discover_topics(const DdsOptions& options, double seconds) {
  dds::DomainParticipantQos qos = checked_participant_qos(options);
  qos.name("robodds-topics");
  DiscoveryListener listener;  // declared before the participant: outlives it
  // Only discovery callbacks: leave data_on_readers out of the mask (it would swallow data).
  ParticipantPtr participant =
      create_participant(options.domain_id, qos, &listener, dds::StatusMask::none(), options.participant_profile);
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  participant.reset();  // no callback runs once it returns
  return listener.topics();
}

}  // namespace robodds
