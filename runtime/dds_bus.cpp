#include "runtime/dds_bus.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/log/Log.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/common/InstanceHandle.h>
#include <fastrtps/utils/IPLocator.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <vector>

#include "runtime/error.hpp"
#include "runtime/log.hpp"
#include "runtime/type_support.hpp"

namespace robodds {
namespace dds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

/// Collects Fast DDS log entries so a rejected XML file can be reported in one line.
class CapturingConsumer : public dds::LogConsumer {
 public:
  void Consume(const dds::Log::Entry& entry) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (entry.kind == dds::Log::Kind::Error) {
      messages_.push_back(entry.message);
    }
  }
  std::vector<std::string> take() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::move(messages_);
  }

 private:
  std::mutex mutex_;
  std::vector<std::string> messages_;
};

CapturingConsumer* install_log_consumer() {
  static CapturingConsumer* consumer = [] {
    auto owned = std::make_unique<CapturingConsumer>();
    CapturingConsumer* raw = owned.get();
    dds::Log::ClearConsumers();
    dds::Log::RegisterConsumer(std::move(owned));
    dds::Log::SetVerbosity(dds::Log::Kind::Error);
    return raw;
  }();
  return consumer;
}

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

std::string ms_text(const eprosima::fastrtps::Duration_t& d) { return std::to_string(d.to_ns() / 1000000) + " ms"; }

/// The policies that decide writer/reader compatibility, in one short text for error messages,
/// e.g. "RELIABLE/TRANSIENT_LOCAL" or "RELIABLE/VOLATILE/deadline 300 ms/liveliness MANUAL_BY_TOPIC 1000 ms".
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

std::string prefix_key(const rtps::GuidPrefix_t& prefix) {
  std::ostringstream out;
  out << prefix;
  return out.str();
}

/// What discovery told this participant about its peers: participant names (so that reports can
/// say which host a writer lives on) and the QoS each remote endpoint offers or requests per
/// topic (so that an incompatible-QoS report shows both sides). Filled by Fast DDS's discovery
/// thread; only stores, never calls back into DDS.
class PeerDirectory : public dds::DomainParticipantListener {
 public:
  void on_participant_discovery(dds::DomainParticipant*, rtps::ParticipantDiscoveryInfo&& info) override {
    const std::string name = info.info.m_participantName.to_string();
    const std::string key = prefix_key(info.info.m_guid.guidPrefix);
    std::lock_guard<std::mutex> lock(mutex_);
    switch (info.status) {
      case rtps::ParticipantDiscoveryInfo::DISCOVERED_PARTICIPANT:
        names_[key] = name;
        alive_.insert(key);
        break;
      case rtps::ParticipantDiscoveryInfo::DROPPED_PARTICIPANT:
        // Dropped = its lease expired without a goodbye: the host died or its network did.
        log::warn("dds", "participant '" + name + "' dropped: no announcement within its lease (host or network down?)");
        alive_.erase(key);
        break;
      case rtps::ParticipantDiscoveryInfo::REMOVED_PARTICIPANT:
        alive_.erase(key);
        break;
      default:
        break;
    }
  }
  void on_publisher_discovery(dds::DomainParticipant*, rtps::WriterDiscoveryInfo&& info) override {
    const auto& q = info.info.m_qos;
    remember(writers_, info.info.topicName().to_string(), info.info.guid(),
             info.status != rtps::WriterDiscoveryInfo::REMOVED_WRITER,
             describe_qos(q.m_reliability, q.m_durability, q.m_deadline, q.m_liveliness));
  }
  void on_subscriber_discovery(dds::DomainParticipant*, rtps::ReaderDiscoveryInfo&& info) override {
    const auto& q = info.info.m_qos;
    remember(readers_, info.info.topicName().to_string(), info.info.guid(),
             info.status != rtps::ReaderDiscoveryInfo::REMOVED_READER,
             describe_qos(q.m_reliability, q.m_durability, q.m_deadline, q.m_liveliness));
  }

  /// "'control'" for a participant named "robodds-control" (the host names participants
  /// "robodds-<group>"), another participant's full name, or its GUID prefix if not yet known.
  std::string who(const rtps::GUID_t& guid) const {
    const std::string key = prefix_key(guid.guidPrefix);
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = names_.find(key);
    if (it == names_.end()) {
      return "participant " + key;
    }
    const std::string& name = it->second;
    return "'" + (name.rfind("robodds-", 0) == 0 ? name.substr(8) : name) + "'";
  }

  /// Remote endpoints of `topic` whose QoS differs from `local` (the suspects of a mismatch;
  /// all of them if none differs), e.g. "BEST_EFFORT/TRANSIENT_LOCAL from 'control'".
  std::string remote_qos(const std::string& topic, bool of_writers, const std::string& local) const {
    std::vector<std::pair<std::string, rtps::GUID_t>> found;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const auto& table = of_writers ? writers_ : readers_;
      auto it = table.find(topic);
      if (it != table.end()) {
        for (const auto& [guid_key, entry] : it->second) {
          found.push_back(entry);
        }
      }
    }
    const bool any_differs = std::any_of(found.begin(), found.end(), [&](const auto& e) { return e.first != local; });
    std::string out;
    for (const auto& [qos, guid] : found) {
      if (!any_differs || qos != local) {
        out += (out.empty() ? "" : ", ") + qos + " from " + who(guid);
      }
    }
    return out.empty() ? std::string("(not discovered yet)") : out;
  }

  std::size_t participants_alive() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return alive_.size();
  }

 private:
  using Table = std::map<std::string, std::map<std::string, std::pair<std::string, rtps::GUID_t>>>;
  void remember(Table& table, const std::string& topic, const rtps::GUID_t& guid, bool present, const std::string& qos) {
    std::ostringstream key;
    key << guid;
    std::lock_guard<std::mutex> lock(mutex_);
    if (present) {
      table[topic][key.str()] = {qos, guid};
    } else {
      table[topic].erase(key.str());
    }
  }

  mutable std::mutex mutex_;
  std::map<std::string, std::string> names_;  // GUID prefix -> participant name
  std::set<std::string> alive_;
  Table writers_;
  Table readers_;
};

/// Match state of one local endpoint, kept for the report appended to lockstep timeouts. The
/// remote side of an incompatibility is looked up when the text is built, not when Fast DDS
/// reports it: the incompatible-QoS callback can come before discovery reports the remote QoS.
class MatchState {
 public:
  MatchState(std::string topic, bool reader, const PeerDirectory* peers)
      : topic_(std::move(topic)), reader_(reader), peers_(peers) {}

  std::atomic<int> matched{0};

  void set_incompatible(dds::QosPolicyId_t policy, std::string local_qos) {
    std::lock_guard<std::mutex> lock(mutex_);
    policy_ = policy;
    local_qos_ = std::move(local_qos);
    incompatible_ = true;
  }
  /// e.g. "incompatible QoS RELIABILITY: this reader requests RELIABLE/..., writers offer
  /// BEST_EFFORT/... from 'control'"; empty if no incompatibility was reported.
  std::string incompatible() const {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!incompatible_) {
      return "";
    }
    return "incompatible QoS " + policy_name(policy_) + (reader_ ? ": this reader requests " : ": this writer offers ") +
           local_qos_ + (reader_ ? ", writers offer " : ", readers request ") + peers_->remote_qos(topic_, reader_, local_qos_);
  }

 private:
  std::string topic_;
  bool reader_;
  const PeerDirectory* peers_;
  mutable std::mutex mutex_;
  bool incompatible_ = false;
  dds::QosPolicyId_t policy_ = dds::INVALID_QOS_POLICY_ID;
  std::string local_qos_;
};

class ReaderListener : public dds::DataReaderListener {
 public:
  ReaderListener(std::string type_name, std::string topic, const PeerDirectory* peers)
      : topic_(std::move(topic)), peers_(peers), match_(topic_, true, peers) {
    type_ = dds::TypeSupport(make_type_support(type_name));
    buffer_ = type_->createData();
  }
  ~ReaderListener() override { type_->deleteData(buffer_); }

  void add(SampleCallback on_sample, ReaderEventCallback on_event) {
    std::lock_guard<std::mutex> lock(mutex_);
    sample_callbacks_.push_back(std::move(on_sample));
    event_callbacks_.push_back(std::move(on_event));
  }

  void on_data_available(dds::DataReader* reader) override {
    std::lock_guard<std::mutex> lock(mutex_);
    dds::SampleInfo info;
    while (reader->take_next_sample(buffer_, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) {
        continue;
      }
      for (const SampleCallback& callback : sample_callbacks_) {
        callback(buffer_);
      }
    }
  }

  void on_subscription_matched(dds::DataReader*, const dds::SubscriptionMatchedStatus& status) override {
    match_.matched = status.current_count;
    const std::string who = peers_->who(rtps::iHandle2GUID(status.last_publication_handle));
    // Debug only: at the end of every multi-process run all writers leave; a writer that
    // disappears while the run goes on is reported by liveliness (state, command) instead.
    log::debug("dds", topic_ + ": writer of " + who + (status.current_count_change > 0 ? " matched" : " unmatched") +
                          " (matched writers: " + std::to_string(status.current_count) + ")");
  }

  void on_requested_incompatible_qos(dds::DataReader* reader, const dds::RequestedIncompatibleQosStatus& status) override {
    const auto& q = reader->get_qos();
    match_.set_incompatible(status.last_policy_id, describe_qos(q.reliability(), q.durability(), q.deadline(), q.liveliness()));
    event(match_.incompatible());
  }
  void on_requested_deadline_missed(dds::DataReader*, const dds::RequestedDeadlineMissedStatus& status) override {
    if (status.total_count_change > 0 && (status.total_count == 1 || status.total_count % 100 == 0)) {
      event("deadline missed (" + std::to_string(status.total_count) + " so far)");
    }
  }
  /// A writer whose lease expires (its process hangs, its host or link is down) goes from alive
  /// to not alive; when its assertions come back it goes back to alive. A writer that leaves
  /// for good (deleted, participant gone) only lowers alive_count and is not a liveliness loss.
  void on_liveliness_changed(dds::DataReader*, const dds::LivelinessChangedStatus& status) override {
    const std::string who = peers_->who(rtps::iHandle2GUID(status.last_publication_handle));
    const std::string counts = " (alive writers: " + std::to_string(status.alive_count) + ", not alive: " +
                               std::to_string(status.not_alive_count) + ")";
    if (status.not_alive_count_change > 0) {
      event("writer of " + who + " lost liveliness" + counts);
    } else if (status.not_alive_count_change < 0 && status.alive_count_change > 0) {
      event("writer of " + who + " regained liveliness" + counts);
    }
  }

  const std::string& topic() const { return topic_; }
  MatchState& match() { return match_; }

 private:
  void event(const std::string& text) {
    std::vector<ReaderEventCallback> callbacks;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      callbacks = event_callbacks_;
    }
    for (const auto& callback : callbacks) {
      if (callback) {
        callback(text);
      }
    }
  }

  std::string topic_;
  const PeerDirectory* peers_;
  dds::TypeSupport type_;
  void* buffer_ = nullptr;
  std::mutex mutex_;
  std::vector<SampleCallback> sample_callbacks_;
  std::vector<ReaderEventCallback> event_callbacks_;
  MatchState match_;
};

class WriterListener : public dds::DataWriterListener {
 public:
  WriterListener(std::string topic, const PeerDirectory* peers)
      : topic_(std::move(topic)), peers_(peers), match_(topic_, false, peers) {}

  void on_publication_matched(dds::DataWriter*, const dds::PublicationMatchedStatus& status) override {
    match_.matched = status.current_count;
    log::debug("dds", topic_ + ": reader of " + peers_->who(rtps::iHandle2GUID(status.last_subscription_handle)) +
                          (status.current_count_change > 0 ? " matched" : " unmatched") +
                          " (matched readers: " + std::to_string(status.current_count) + ")");
  }
  void on_offered_incompatible_qos(dds::DataWriter* writer, const dds::OfferedIncompatibleQosStatus& status) override {
    const auto& q = writer->get_qos();
    match_.set_incompatible(status.last_policy_id, describe_qos(q.reliability(), q.durability(), q.deadline(), q.liveliness()));
    log::warn("dds", topic_ + ": " + match_.incompatible());
  }

  const std::string& topic() const { return topic_; }
  MatchState& match() { return match_; }

 private:
  std::string topic_;
  const PeerDirectory* peers_;
  MatchState match_;
};

class DdsWriter : public WriterHandle {
 public:
  DdsWriter(dds::DataWriter* writer, std::string topic) : writer_(writer), topic_(std::move(topic)) {}
  void write(const void* sample) override {
    if (!writer_->write(const_cast<void*>(sample))) {
      throw RunError("DDS write failed on topic " + topic_);
    }
  }
  const std::string& topic() const override { return topic_; }
  dds::DataWriter* writer() const { return writer_; }

 private:
  dds::DataWriter* writer_;
  std::string topic_;
};

class DdsReader : public ReaderHandle {};

/// The loaded file that defines `<kind profile_name="name">` (for error messages), else `fallback`.
std::string file_defining(const std::vector<std::string>& files, const std::string& name, const std::string& fallback) {
  for (const std::string& file : files) {
    std::ifstream in(file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find("profile_name=\"" + name + "\"") != std::string::npos) {
      return file;
    }
  }
  return fallback;
}

/// Fast DDS 2.9 parses a discovery-server locator with port 0, a port above 65535 (silently
/// truncated) or address 0.0.0.0 and then never reaches the server: discovery just never
/// happens. Reject such a profile at start-up instead, naming the file and the element.
void check_discovery_servers(const dds::DomainParticipantQos& qos, const std::string& profile, const std::string& file) {
  const auto& config = qos.wire_protocol().builtin.discovery_config;
  const std::string where = "participant profile '" + profile + "': discoveryServersList";
  const bool client = config.discoveryProtocol == rtps::DiscoveryProtocol_t::CLIENT ||
                      config.discoveryProtocol == rtps::DiscoveryProtocol_t::SUPER_CLIENT;
  if (client && config.m_DiscoveryServers.empty()) {
    throw ConfigError(located(file, where, "a discovery CLIENT needs at least one <RemoteServer>"));
  }
  for (const auto& server : config.m_DiscoveryServers) {
    const std::string element = where + ": RemoteServer " + prefix_key(server.guidPrefix);
    if (server.metatrafficUnicastLocatorList.empty() && server.metatrafficMulticastLocatorList.empty()) {
      throw ConfigError(located(file, element, "has no locator: add a <metatrafficUnicastLocatorList> with the server's address and port"));
    }
    for (const auto& locator : server.metatrafficUnicastLocatorList) {
      const std::string address = eprosima::fastrtps::rtps::IPLocator::ip_to_string(locator);
      if (locator.port == 0 || locator.port > 65535) {
        throw ConfigError(located(file, element + ": locator " + address,
                                  "port " + std::to_string(locator.port) + " is not a valid port (1-65535)"));
      }
      if (eprosima::fastrtps::rtps::IPLocator::isAny(locator)) {
        throw ConfigError(located(file, element + ": locator " + address + ":" + std::to_string(locator.port),
                                  "address " + address + " is not a server address (give the server's IP)"));
      }
    }
  }
}

/// Loads the files and returns the participant QoS of options.participant_profile, checked.
dds::DomainParticipantQos checked_participant_qos(const DdsOptions& options) {
  load_qos_files(options.qos_files);
  const std::string last = options.qos_files.empty() ? "(no QoS file)" : options.qos_files.back();
  dds::DomainParticipantQos qos;
  if (dds::DomainParticipantFactory::get_instance()->get_participant_qos_from_profile(options.participant_profile, qos) !=
      ReturnCode_t::RETCODE_OK) {
    throw ConfigError(located(last, "participant profile '" + options.participant_profile + "'", "not found in the loaded QoS files"));
  }
  check_discovery_servers(qos, options.participant_profile,
                          file_defining(options.qos_files, options.participant_profile, last));
  return qos;
}

class FastDdsBus : public DdsBus {
 public:
  explicit FastDdsBus(const DdsOptions& options) {
    dds::DomainParticipantQos qos = checked_participant_qos(options);
    auto* factory = dds::DomainParticipantFactory::get_instance();
    qos.name(options.participant_name);
    // Only discovery callbacks (participant names, remote QoS): with an empty mask no entity
    // status reaches this listener, so on_data_available stays with the readers' listeners.
    participant_ = factory->create_participant(options.domain_id, qos, &peers_, dds::StatusMask::none());
    if (participant_ == nullptr) {
      throw RunError("could not create a DDS participant on domain " + std::to_string(options.domain_id) +
                     " with profile '" + options.participant_profile + "'");
    }
    publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
    subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
    const std::string data_file = options.qos_files.empty() ? "(no QoS file)" : options.qos_files.front();
    for (const std::string& profile : required_data_profiles()) {
      dds::DataWriterQos wq;
      dds::DataReaderQos rq;
      if (publisher_->get_datawriter_qos_from_profile(profile, wq) != ReturnCode_t::RETCODE_OK) {
        throw ConfigError(located(data_file, "data_writer profile '" + profile + "'", "not found"));
      }
      if (subscriber_->get_datareader_qos_from_profile(profile, rq) != ReturnCode_t::RETCODE_OK) {
        throw ConfigError(located(data_file, "data_reader profile '" + profile + "'", "not found"));
      }
    }
  }

  ~FastDdsBus() override {
    if (participant_ != nullptr) {
      close_readers();
      participant_->set_listener(nullptr);
      participant_->delete_contained_entities();
      dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
    }
  }

  std::shared_ptr<WriterHandle> writer(const std::string& topic, const std::string& type_name, const std::string& profile) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string key = topic + "|" + profile;
    auto it = writers_.find(key);
    if (it != writers_.end()) {
      return it->second;
    }
    dds::Topic* dds_topic = ensure_topic(topic, type_name);
    auto listener = std::make_unique<WriterListener>(topic, &peers_);
    dds::StatusMask mask = dds::StatusMask::offered_incompatible_qos() << dds::StatusMask::publication_matched();
    dds::DataWriter* writer = publisher_->create_datawriter_with_profile(dds_topic, profile, listener.get(), mask);
    if (writer == nullptr) {
      throw ConfigError("cannot create a writer on " + topic + " with QoS profile '" + profile + "'");
    }
    writer_listeners_[key] = std::move(listener);
    auto handle = std::make_shared<DdsWriter>(writer, topic);
    writers_[key] = handle;
    return handle;
  }

  std::shared_ptr<ReaderHandle> reader(const std::string& topic, const std::string& type_name, const std::string& profile,
                                       SampleCallback on_sample, ReaderEventCallback on_event) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string key = topic + "|" + profile;
    auto it = readers_.find(key);
    if (it == readers_.end()) {
      ensure_topic(topic, type_name);
      PendingReader pending;
      pending.topic = topic;
      pending.profile = profile;
      pending.listener = std::make_unique<ReaderListener>(type_name, topic, &peers_);
      it = readers_.emplace(key, std::move(pending)).first;
    }
    it->second.listener->add(std::move(on_sample), std::move(on_event));
    if (started_) {
      create_reader(it->second);
    }
    return std::make_shared<DdsReader>();
  }

  void start() override {
    std::lock_guard<std::mutex> lock(mutex_);
    started_ = true;
    for (auto& [key, pending] : readers_) {
      create_reader(pending);
    }
  }

  void close_readers() override {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [key, pending] : readers_) {
      if (pending.reader != nullptr) {
        // Waits for a callback in progress on this reader (Fast DDS takes the reader's lock).
        subscriber_->delete_datareader(pending.reader);
        pending.reader = nullptr;
      }
    }
    started_ = false;  // a reader() call after this must not resurrect readers
  }

  void flush(std::chrono::milliseconds timeout) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto deadline = eprosima::fastrtps::Duration_t(static_cast<double>(timeout.count()) / 1000.0);
    for (auto& [key, writer] : writers_) {
      writer->writer()->wait_for_acknowledgments(deadline);
    }
  }

  std::string match_report() override {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> items;
    for (auto& [key, pending] : readers_) {
      if (pending.reader != nullptr) {
        add_match_item(items, pending.topic + " (reader)", pending.listener->match(), "no writer matched");
      }
    }
    for (auto& [key, listener] : writer_listeners_) {
      add_match_item(items, listener->topic() + " (writer)", listener->match(), "no reader matched");
    }
    if (items.empty()) {
      return "";
    }
    const std::size_t peers = peers_.participants_alive();
    std::string out = peers == 0 ? "DDS: no other participant discovered (another domain id, multicast blocked, "
                                   "or discovery server unreachable?)"
                                 : "DDS: " + std::to_string(peers) + " other participant(s) discovered";
    for (const std::string& item : items) {
      out += "; " + item;
    }
    return out;
  }

 private:
  struct PendingReader {
    std::string topic;
    std::string profile;
    std::unique_ptr<ReaderListener> listener;
    dds::DataReader* reader = nullptr;
  };

  /// An incompatible QoS explains a missing match, so it wins over "no match".
  static void add_match_item(std::vector<std::string>& items, const std::string& what, MatchState& match,
                             const std::string& unmatched) {
    const std::string incompatible = match.incompatible();
    if (!incompatible.empty()) {
      items.push_back(what + ": " + incompatible);
    } else if (match.matched == 0) {
      items.push_back(what + ": " + unmatched);
    }
  }

  void create_reader(PendingReader& pending) {
    if (pending.reader != nullptr) {
      return;
    }
    dds::StatusMask mask = dds::StatusMask::data_available() << dds::StatusMask::requested_incompatible_qos()
                           << dds::StatusMask::requested_deadline_missed() << dds::StatusMask::liveliness_changed()
                           << dds::StatusMask::subscription_matched();
    pending.reader = subscriber_->create_datareader_with_profile(topics_.at(pending.topic), pending.profile,
                                                                 pending.listener.get(), mask);
    if (pending.reader == nullptr) {
      throw ConfigError("cannot create a reader on " + pending.topic + " with QoS profile '" + pending.profile + "'");
    }
  }

  dds::Topic* ensure_topic(const std::string& topic, const std::string& type_name) {
    auto it = topics_.find(topic);
    if (it != topics_.end()) {
      return it->second;
    }
    if (registered_types_.count(type_name) == 0) {
      dds::TopicDataType* type = make_type_support(type_name);
      if (type == nullptr) {
        throw ConfigError("topic " + topic + ": unknown type " + type_name);
      }
      dds::TypeSupport support(type);
      if (support.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
        throw RunError("could not register type " + type_name);
      }
      registered_types_.insert(type_name);
    }
    dds::Topic* created = participant_->create_topic(topic, type_name, dds::TOPIC_QOS_DEFAULT);
    if (created == nullptr) {
      throw RunError("could not create topic " + topic);
    }
    topics_[topic] = created;
    return created;
  }

  // Declared before participant_'s users: the participant (deleted in the destructor body)
  // calls it until then, so it must outlive the participant.
  PeerDirectory peers_;
  std::mutex mutex_;
  dds::DomainParticipant* participant_ = nullptr;
  dds::Publisher* publisher_ = nullptr;
  dds::Subscriber* subscriber_ = nullptr;
  std::set<std::string> registered_types_;
  std::map<std::string, dds::Topic*> topics_;
  std::map<std::string, std::shared_ptr<DdsWriter>> writers_;
  std::map<std::string, std::unique_ptr<WriterListener>> writer_listeners_;
  std::map<std::string, PendingReader> readers_;
  bool started_ = false;
};

}  // namespace

const std::vector<std::string>& required_data_profiles() {
  static const std::vector<std::string> profiles = {"sensor", "state", "command", "mission", "lockstep", "lockstep_local", "monitor"};
  return profiles;
}

void load_qos_files(const std::vector<std::string>& files) {
  static std::mutex mutex;
  static std::set<std::string> loaded;
  std::lock_guard<std::mutex> lock(mutex);
  CapturingConsumer* consumer = install_log_consumer();
  for (const std::string& file : files) {
    if (loaded.count(file) != 0) {
      continue;
    }
    if (!std::ifstream(file).good()) {
      throw ConfigError(located(file, "", "QoS profile file not found or not readable"));
    }
    consumer->take();
    const ReturnCode_t rc = dds::DomainParticipantFactory::get_instance()->load_XML_profiles_file(file);
    dds::Log::Flush();
    // Fast DDS logs the real problem first, then one "Error parsing ..." line per enclosing
    // element and per later profile: the first two name the element and where it sits.
    std::string reasons;
    const std::vector<std::string> messages = consumer->take();
    for (std::size_t i = 0; i < messages.size() && i < 2; ++i) {
      reasons += (reasons.empty() ? "" : "; ") + messages[i];
    }
    if (rc != ReturnCode_t::RETCODE_OK) {
      throw ConfigError(located(file, "", "rejected by Fast DDS (2.9 XML schema): " +
                                              (reasons.empty() ? std::string("malformed XML") : reasons)));
    }
    if (!messages.empty()) {
      // Loaded "successfully" but with errors, e.g. a profile name already defined by an earlier
      // file: Fast DDS keeps the first definition and drops this one, which would silently run
      // with other QoS than the file says.
      throw ConfigError(located(file, "", "Fast DDS reported errors while loading it: " + reasons));
    }
    loaded.insert(file);
  }
}

void check_participant_profile(const DdsOptions& options) { checked_participant_qos(options); }

std::unique_ptr<DdsBus> make_dds_bus(const DdsOptions& options) { return std::make_unique<FastDdsBus>(options); }

}  // namespace robodds
