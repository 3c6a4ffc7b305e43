#pragma once
// The Fast DDS listeners of the bus's readers and writers: sample delivery, QoS events and
// match tracking (runtime-internal; includes Fast DDS).

#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "runtime/bus/bus.hpp"
#include "runtime/dds/match_report.hpp"

namespace robodds {
namespace dds = eprosima::fastdds::dds;

/// The listener of the one DDS reader per (topic, profile): hands every valid sample to each
/// local subscriber's callback and QoS events (incompatible QoS, deadline, liveliness) to their
/// event callbacks.
class ReaderListener : public dds::DataReaderListener {
 public:
  ReaderListener(const std::string& type_name, std::string topic, PeerDirectory* peers);
  ~ReaderListener() override;

  void add(SampleCallback on_sample, ReaderEventCallback on_event);

  void on_data_available(dds::DataReader* reader) override;
  void on_subscription_matched(dds::DataReader*, const dds::SubscriptionMatchedStatus& status) override;
  void on_requested_incompatible_qos(dds::DataReader* reader, const dds::RequestedIncompatibleQosStatus& status) override;
  void on_requested_deadline_missed(dds::DataReader*, const dds::RequestedDeadlineMissedStatus& status) override;
  /// A writer whose lease expires (its process hangs, its host or link is down) goes from alive
  /// to not alive; when its assertions come back it goes back to alive. A writer that leaves
  /// for good (deleted, participant gone) only lowers alive_count and is not a liveliness loss.
  void on_liveliness_changed(dds::DataReader*, const dds::LivelinessChangedStatus& status) override;

  const MatchState& match() const { return match_; }

 private:
  void event(const std::string& text);

  std::string topic_;
  PeerDirectory* peers_;
  dds::TypeSupport type_;
  void* buffer_ = nullptr;
  std::mutex mutex_;
  std::vector<SampleCallback> sample_callbacks_;
  std::vector<ReaderEventCallback> event_callbacks_;
  MatchState match_;
  // The writer of the previous sample and its SampleMeta::writer_id (0: none yet): most samples
  // come from the same writer as the one before, and PeerDirectory::writer_id() hashes and
  // locks. Guarded by mutex_.
  rtps::GUID_t last_writer_;
  std::uint64_t last_writer_id_ = 0;
};

/// The listener of one DDS writer: tracks its matches and warns about an incompatible QoS.
class WriterListener : public dds::DataWriterListener {
 public:
  WriterListener(std::string topic, const PeerDirectory* peers);

  void on_publication_matched(dds::DataWriter*, const dds::PublicationMatchedStatus& status) override;
  void on_offered_incompatible_qos(dds::DataWriter* writer, const dds::OfferedIncompatibleQosStatus& status) override;

  const MatchState& match() const { return match_; }

 private:
  std::string topic_;
  const PeerDirectory* peers_;
  MatchState match_;
};

}  // namespace robodds
