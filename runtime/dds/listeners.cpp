#include "runtime/dds/listeners.hpp"

#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/rtps/common/InstanceHandle.h>

#include "runtime/dds/text.hpp"
#include "runtime/base/log.hpp"
#include "runtime/dds/type_support.hpp"

namespace robodds {
namespace rtps = eprosima::fastrtps::rtps;
using eprosima::fastrtps::types::ReturnCode_t;

ReaderListener::ReaderListener(const std::string& type_name, std::string topic, PeerDirectory* peers)
    : topic_(std::move(topic)), peers_(peers), match_(topic_, true, peers) {
  type_ = dds::TypeSupport(make_type_support(type_name));
  buffer_ = type_->createData();
}

ReaderListener::~ReaderListener() { type_->deleteData(buffer_); }

void ReaderListener::add(SampleCallback on_sample, ReaderEventCallback on_event) {
  std::lock_guard<std::mutex> lock(mutex_);
  sample_callbacks_.push_back(std::move(on_sample));
  event_callbacks_.push_back(std::move(on_event));
}

void ReaderListener::on_data_available(dds::DataReader* reader) {
  std::lock_guard<std::mutex> lock(mutex_);
  dds::SampleInfo info;
  // Fast DDS calls this once per received sample. Take as many samples as the reader holds, not
  // until a take finds none: that last take cost a lock, a clock reading and an instance lookup
  // for nothing, once per sample. A sample that arrives meanwhile comes with a call of its own.
  // One arrival time for the samples of one call (they arrived within microseconds).
  const std::int64_t arrived_ns = monotonic_now_ns();
  for (std::uint64_t held = reader->get_unread_count(); held > 0; --held) {
    if (reader->take_next_sample(buffer_, &info) != ReturnCode_t::RETCODE_OK) {
      break;
    }
    if (!info.valid_data) {
      continue;
    }
    const rtps::GUID_t writer = rtps::iHandle2GUID(info.publication_handle);
    if (last_writer_id_ == 0 || writer != last_writer_) {
      last_writer_ = writer;
      last_writer_id_ = peers_->writer_id(writer);
    }
    const SampleMeta meta{last_writer_id_, arrived_ns};
    for (const SampleCallback& callback : sample_callbacks_) {
      callback(buffer_, meta);
    }
  }
}

void ReaderListener::on_subscription_matched(dds::DataReader*, const dds::SubscriptionMatchedStatus& status) {
  match_.matched = status.current_count;
  const std::string who = peers_->who(rtps::iHandle2GUID(status.last_publication_handle));
  // Debug only: at the end of every multi-process run all writers leave; a writer that
  // disappears while the run goes on is reported by liveliness (state, command) instead.
  log::debug("dds", topic_ + ": writer of " + who + (status.current_count_change > 0 ? " matched" : " unmatched") +
                        " (matched writers: " + std::to_string(status.current_count) + ")");
}

void ReaderListener::on_requested_incompatible_qos(dds::DataReader* reader, const dds::RequestedIncompatibleQosStatus& status) {
  const auto& q = reader->get_qos();
  match_.set_incompatible(status.last_policy_id, describe_qos(q.reliability(), q.durability(), q.deadline(), q.liveliness()));
  event(match_.incompatible());
}

void ReaderListener::on_requested_deadline_missed(dds::DataReader*, const dds::RequestedDeadlineMissedStatus& status) {
  if (status.total_count_change > 0 && (status.total_count == 1 || status.total_count % 100 == 0)) {
    event("deadline missed (" + std::to_string(status.total_count) + " so far)");
  }
}

void ReaderListener::on_liveliness_changed(dds::DataReader*, const dds::LivelinessChangedStatus& status) {
  const std::string who = peers_->who(rtps::iHandle2GUID(status.last_publication_handle));
  const std::string counts = " (alive writers: " + std::to_string(status.alive_count) + ", not alive: " +
                             std::to_string(status.not_alive_count) + ")";
  if (status.not_alive_count_change > 0) {
    event("writer of " + who + " lost liveliness" + counts);
  } else if (status.not_alive_count_change < 0 && status.alive_count_change > 0) {
    event("writer of " + who + " regained liveliness" + counts);
  }
}

void ReaderListener::event(const std::string& text) {
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

WriterListener::WriterListener(std::string topic, const PeerDirectory* peers)
    : topic_(std::move(topic)), peers_(peers), match_(topic_, false, peers) {}

void WriterListener::on_publication_matched(dds::DataWriter*, const dds::PublicationMatchedStatus& status) {
  match_.matched = status.current_count;
  log::debug("dds", topic_ + ": reader of " + peers_->who(rtps::iHandle2GUID(status.last_subscription_handle)) +
                        (status.current_count_change > 0 ? " matched" : " unmatched") +
                        " (matched readers: " + std::to_string(status.current_count) + ")");
}

void WriterListener::on_offered_incompatible_qos(dds::DataWriter* writer, const dds::OfferedIncompatibleQosStatus& status) {
  const auto& q = writer->get_qos();
  match_.set_incompatible(status.last_policy_id, describe_qos(q.reliability(), q.durability(), q.deadline(), q.liveliness()));
  log::warn("dds", topic_ + ": " + match_.incompatible());
}

}  // namespace robodds
