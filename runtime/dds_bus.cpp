#include "runtime/dds_bus.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
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

#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <vector>

#include "runtime/error.hpp"
#include "runtime/log.hpp"
#include "runtime/type_support.hpp"

namespace robodds {
namespace dds = eprosima::fastdds::dds;
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

std::string describe_qos(const dds::ReliabilityQosPolicy& r, const dds::DurabilityQosPolicy& d,
                         const dds::DeadlineQosPolicy& dl) {
  std::string out = r.kind == dds::RELIABLE_RELIABILITY_QOS ? "RELIABLE" : "BEST_EFFORT";
  out += d.kind == dds::TRANSIENT_LOCAL_DURABILITY_QOS ? "/TRANSIENT_LOCAL" : (d.kind == dds::VOLATILE_DURABILITY_QOS ? "/VOLATILE" : "/other");
  if (dl.period != eprosima::fastrtps::c_TimeInfinite) {
    out += "/deadline " + std::to_string(dl.period.to_ns() / 1000000) + " ms";
  }
  return out;
}

class ReaderListener : public dds::DataReaderListener {
 public:
  ReaderListener(std::string type_name, std::string topic) : topic_(std::move(topic)) {
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

  void on_requested_incompatible_qos(dds::DataReader* reader, const dds::RequestedIncompatibleQosStatus& status) override {
    const auto& q = reader->get_qos();
    event("incompatible QoS with a writer: " + policy_name(status.last_policy_id) + " (this reader requests " +
          describe_qos(q.reliability(), q.durability(), q.deadline()) + ")");
  }
  void on_requested_deadline_missed(dds::DataReader*, const dds::RequestedDeadlineMissedStatus& status) override {
    if (status.total_count_change > 0 && (status.total_count == 1 || status.total_count % 100 == 0)) {
      event("deadline missed (" + std::to_string(status.total_count) + " so far)");
    }
  }
  void on_liveliness_changed(dds::DataReader*, const dds::LivelinessChangedStatus& status) override {
    if (status.not_alive_count_change > 0) {
      event("liveliness lost: a writer stopped asserting liveliness (alive writers: " + std::to_string(status.alive_count) + ")");
    } else if (status.alive_count_change > 0 && status.not_alive_count > 0) {
      event("liveliness recovered (alive writers: " + std::to_string(status.alive_count) + ")");
    }
  }

  const std::string& topic() const { return topic_; }

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
  dds::TypeSupport type_;
  void* buffer_ = nullptr;
  std::mutex mutex_;
  std::vector<SampleCallback> sample_callbacks_;
  std::vector<ReaderEventCallback> event_callbacks_;
};

class WriterListener : public dds::DataWriterListener {
 public:
  explicit WriterListener(std::string topic) : topic_(std::move(topic)) {}
  void on_offered_incompatible_qos(dds::DataWriter* writer, const dds::OfferedIncompatibleQosStatus& status) override {
    const auto& q = writer->get_qos();
    log::warn("dds", topic_ + ": a reader requests incompatible QoS: " + policy_name(status.last_policy_id) +
                         " (this writer offers " + describe_qos(q.reliability(), q.durability(), q.deadline()) + ")");
  }

 private:
  std::string topic_;
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

class FastDdsBus : public DdsBus {
 public:
  explicit FastDdsBus(const DdsOptions& options) {
    load_qos_files(options.qos_files);
    auto* factory = dds::DomainParticipantFactory::get_instance();
    const std::string file = options.qos_files.empty() ? "(no QoS file)" : options.qos_files.back();
    dds::DomainParticipantQos qos;
    if (factory->get_participant_qos_from_profile(options.participant_profile, qos) != ReturnCode_t::RETCODE_OK) {
      throw ConfigError(located(file, "participant profile '" + options.participant_profile + "'", "not found in the loaded QoS files"));
    }
    qos.name(options.participant_name);
    participant_ = factory->create_participant(options.domain_id, qos);
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
    auto listener = std::make_unique<WriterListener>(topic);
    dds::StatusMask mask = dds::StatusMask::offered_incompatible_qos();
    dds::DataWriter* writer = publisher_->create_datawriter_with_profile(dds_topic, profile, listener.get(), mask);
    if (writer == nullptr) {
      throw ConfigError("cannot create a writer on " + topic + " with QoS profile '" + profile + "'");
    }
    writer_listeners_.push_back(std::move(listener));
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
      pending.listener = std::make_unique<ReaderListener>(type_name, topic);
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

  void flush(std::chrono::milliseconds timeout) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto deadline = eprosima::fastrtps::Duration_t(static_cast<double>(timeout.count()) / 1000.0);
    for (auto& [key, writer] : writers_) {
      writer->writer()->wait_for_acknowledgments(deadline);
    }
  }

 private:
  struct PendingReader {
    std::string topic;
    std::string profile;
    std::unique_ptr<ReaderListener> listener;
    dds::DataReader* reader = nullptr;
  };

  void create_reader(PendingReader& pending) {
    if (pending.reader != nullptr) {
      return;
    }
    dds::StatusMask mask = dds::StatusMask::data_available() << dds::StatusMask::requested_incompatible_qos()
                           << dds::StatusMask::requested_deadline_missed() << dds::StatusMask::liveliness_changed();
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

  std::mutex mutex_;
  dds::DomainParticipant* participant_ = nullptr;
  dds::Publisher* publisher_ = nullptr;
  dds::Subscriber* subscriber_ = nullptr;
  std::set<std::string> registered_types_;
  std::map<std::string, dds::Topic*> topics_;
  std::map<std::string, std::shared_ptr<DdsWriter>> writers_;
  std::vector<std::unique_ptr<WriterListener>> writer_listeners_;
  std::map<std::string, PendingReader> readers_;
  bool started_ = false;
};

}  // namespace

const std::vector<std::string>& required_data_profiles() {
  static const std::vector<std::string> profiles = {"sensor", "state", "command", "mission", "lockstep", "monitor"};
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
    std::string reasons;
    for (const std::string& message : consumer->take()) {
      reasons += (reasons.empty() ? "" : "; ") + message;
    }
    if (rc != ReturnCode_t::RETCODE_OK) {
      throw ConfigError(located(file, "", "rejected by Fast DDS (2.9 XML schema): " +
                                              (reasons.empty() ? std::string("malformed XML") : reasons)));
    }
    loaded.insert(file);
  }
}

std::unique_ptr<DdsBus> make_dds_bus(const DdsOptions& options) { return std::make_unique<FastDdsBus>(options); }

}  // namespace robodds
