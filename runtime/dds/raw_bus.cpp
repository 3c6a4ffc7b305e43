#include "runtime/dds/raw_bus.hpp"
#include "runtime/dds/participant_topics.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <mutex>
#include <set>

#include "runtime/base/error.hpp"
#include "runtime/dds/dds_sample_codec.hpp"
#include "runtime/dds/participant.hpp"
#include "runtime/dds/qos_files.hpp"
#include "runtime/dds/raw_type.hpp"
#include "runtime/dds/text.hpp"
#include "runtime/health/shutdown_watchdog.hpp"

namespace robodds {
namespace dds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

std::int64_t wall_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

class RawReaderListener : public dds::DataReaderListener {
 public:
  RawReaderListener(std::string topic, RawSampleCallback on_sample, ReaderEventCallback on_event)
      : topic_(std::move(topic)), on_sample_(std::move(on_sample)), on_event_(std::move(on_event)) {}

  void on_data_available(dds::DataReader* reader) override {
    dds::SampleInfo info;
    while (reader->take_next_sample(&buffer_, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) {
        continue;  // a dispose or unregister: no payload
      }
      RawSample sample;
      sample.data = buffer_.bytes.data();
      sample.size = buffer_.bytes.size();
      sample.source_time_ns = info.source_timestamp.to_ns();
      // Fast DDS stamps it (system clock) in the RTPS reader; a path that does not would leave 0.
      sample.reception_time_ns = info.reception_timestamp == rtps::Time_t() ? wall_now_ns() : info.reception_timestamp.to_ns();
      const rtps::GUID_t writer = info.sample_identity.writer_guid();
      std::memcpy(sample.writer_guid.data(), writer.guidPrefix.value, 12);
      std::memcpy(sample.writer_guid.data() + 12, writer.entityId.value, 4);
      std::memcpy(sample.instance.data(), info.instance_handle.value, 16);
      on_sample_(sample);
    }
  }
  void on_subscription_matched(dds::DataReader*, const dds::SubscriptionMatchedStatus& status) override {
    if (on_writers_) {
      on_writers_(status.current_count);
    }
  }
  /// Before the reader exists: the listener's threads read it without a lock.
  void set_on_writers(RawWritersCallback on_writers) { on_writers_ = std::move(on_writers); }
  void on_requested_incompatible_qos(dds::DataReader*, const dds::RequestedIncompatibleQosStatus& status) override {
    if (on_event_) {
      on_event_("a writer offers an incompatible QoS (policy id " + std::to_string(status.last_policy_id) + ")");
    }
  }

 private:
  std::string topic_;
  RawSampleCallback on_sample_;
  ReaderEventCallback on_event_;
  RawWritersCallback on_writers_;
  RawPayload buffer_;  // reused: no allocation once it has the largest sample's size
};

class FastDdsRawWriter : public RawWriter {
 public:
  explicit FastDdsRawWriter(dds::DataWriter* writer) : writer_(writer) {}
  bool write(const std::uint8_t* data, std::size_t size) override {
    std::lock_guard<std::mutex> lock(mutex_);
    sample_.bytes.assign(data, data + size);
    return writer_->write(&sample_);  // DataWriter::write(void*) returns bool in 2.9
  }
  int matched_readers() const override {
    dds::PublicationMatchedStatus status;
    writer_->get_publication_matched_status(status);
    return status.current_count;
  }
  bool wait_acknowledged(std::chrono::milliseconds timeout) override {
    return writer_->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(std::chrono::duration<double>(timeout).count())) ==
           ReturnCode_t::RETCODE_OK;
  }
  dds::DataWriter* writer() const { return writer_; }

 private:
  dds::DataWriter* writer_;  // owned by the participant
  std::mutex mutex_;
  RawPayload sample_;
};

class FastDdsRawBus : public RawBus {
 public:
  explicit FastDdsRawBus(const DdsOptions& options) {
    dds::DomainParticipantQos qos = checked_participant_qos(options);
    qos.name(options.participant_name);
    participant_ = create_participant(options.domain_id, qos, nullptr, dds::StatusMask::none(), options.participant_profile);
    publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
    subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
    if (publisher_ == nullptr || subscriber_ == nullptr) {
      throw RunError("could not create a DDS publisher and subscriber on domain " + std::to_string(options.domain_id));
    }
  }

  ~FastDdsRawBus() override {
    close_readers();
    std::lock_guard<std::mutex> lock(mutex_);
    ShutdownWatchdog watchdog("emptying the raw DDS writers' histories");
    for (auto& [topic, writer] : writers_) {
      std::size_t removed = 0;
      writer->writer()->clear_history(&removed);  // see FastDdsBus::clear_writer_histories()
    }
  }

  void reader(const std::string& topic, const std::string& type_name, const std::string& profile, RawSampleCallback on_sample,
              ReaderEventCallback on_event) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (readers_.count(topic) != 0) {
      throw ConfigError("topic " + topic + " is read twice by one raw bus");
    }
    ensure_topic(topic, type_name);
    Reader r;
    r.profile = profile;
    r.listener = std::make_unique<RawReaderListener>(topic, std::move(on_sample), std::move(on_event));
    auto& entry = readers_[topic] = std::move(r);
    if (started_) {
      create_reader(topic, entry);
    }
  }

  void watch_writers(const std::string& topic, RawWritersCallback on_writers) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = readers_.find(topic);
    if (it == readers_.end() || started_) {
      throw ConfigError("watch_writers(" + topic + "): call it after reader() and before start()");
    }
    it->second.listener->set_on_writers(std::move(on_writers));
  }

  void start() override {
    std::lock_guard<std::mutex> lock(mutex_);
    started_ = true;
    for (auto& [topic, entry] : readers_) {
      create_reader(topic, entry);
    }
  }

  void close_readers() override {
    std::lock_guard<std::mutex> lock(mutex_);
    ShutdownWatchdog watchdog("deleting the raw DDS readers (each waits for its callback in progress)");
    for (auto& [topic, entry] : readers_) {
      if (entry.reader != nullptr) {
        subscriber_->delete_datareader(entry.reader);
        entry.reader = nullptr;
      }
    }
    started_ = false;
  }

  std::shared_ptr<RawWriter> writer(const std::string& topic, const std::string& type_name, const std::string& profile,
                                    std::int32_t min_history_depth) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string id = topic + "|" + profile + "|" + std::to_string(min_history_depth);
    auto it = writers_.find(id);
    if (it != writers_.end()) {
      return it->second;
    }
    dds::DataWriterQos qos;
    if (publisher_->get_datawriter_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) {
      throw ConfigError("cannot write " + topic + ": no data_writer QoS profile '" + profile + "' in the QoS files");
    }
    // Not for transient-local profiles: their history is what a late reader receives (the last
    // mission of each robot, not the last 256).
    if (qos.durability().kind == dds::VOLATILE_DURABILITY_QOS && qos.history().kind == dds::KEEP_LAST_HISTORY_QOS &&
        qos.history().depth < min_history_depth) {
      qos.history().depth = min_history_depth;
      qos.resource_limits().max_samples_per_instance = std::max(qos.resource_limits().max_samples_per_instance, min_history_depth);
      if (qos.resource_limits().max_samples > 0) {  // 0: unlimited
        qos.resource_limits().max_samples = std::max(qos.resource_limits().max_samples, min_history_depth);
      }
    }
    dds::DataWriter* created = publisher_->create_datawriter(ensure_topic(topic, type_name), qos);
    if (created == nullptr) {
      const std::string reasons = take_dds_errors();
      throw ConfigError("cannot create a writer on " + topic + " with QoS profile '" + profile + "'" +
                        (reasons.empty() ? std::string() : ": Fast DDS: " + reasons));
    }
    auto handle = std::make_shared<FastDdsRawWriter>(created);
    writers_[id] = handle;
    return handle;
  }

 private:
  struct Reader {
    std::string profile;
    std::unique_ptr<RawReaderListener> listener;
    dds::DataReader* reader = nullptr;  // owned by participant_
  };

  void create_reader(const std::string& topic, Reader& entry) {
    if (entry.reader != nullptr) {
      return;
    }
    dds::DataReaderQos qos;
    if (subscriber_->get_datareader_qos_from_profile(entry.profile, qos) != ReturnCode_t::RETCODE_OK) {
      throw ConfigError("cannot read " + topic + ": no data_reader QoS profile '" + entry.profile + "' in the QoS files");
    }
    entry.reader = subscriber_->create_datareader(topics_.at(topic), raw_reader_qos(qos), entry.listener.get(),
                                                  dds::StatusMask::data_available() << dds::StatusMask::requested_incompatible_qos()
                                                      << dds::StatusMask::subscription_matched());
    if (entry.reader == nullptr) {
      const std::string reasons = take_dds_errors();
      throw ConfigError("cannot create a reader on " + topic + " with QoS profile '" + entry.profile + "'" +
                        (reasons.empty() ? std::string() : ": Fast DDS: " + reasons));
    }
  }

  dds::Topic* ensure_topic(const std::string& topic, const std::string& type_name) {
    // RawPayloadType throws ConfigError for a type we do not know.
    return topics_.ensure(*participant_, topic, type_name, [](const std::string& name) { return new RawPayloadType(name); });
  }

  // Declared before participant_: the readers' listeners outlive it (members die in reverse order).
  std::mutex mutex_;
  std::map<std::string, Reader> readers_;
  std::map<std::string, std::shared_ptr<FastDdsRawWriter>> writers_;
  ParticipantTopics topics_;
  ParticipantPtr participant_;
  dds::Publisher* publisher_ = nullptr;    // owned by participant_
  dds::Subscriber* subscriber_ = nullptr;  // owned by participant_
  bool started_ = false;
};

}  // namespace

std::unique_ptr<RawBus> make_raw_bus(const DdsOptions& options) {
  install_dds_sample_codec();  // a tool that sets up DDS can also encode and decode samples
  return std::make_unique<FastDdsRawBus>(options);
}

}  // namespace robodds
