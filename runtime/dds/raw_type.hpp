#pragma once
// A Fast DDS type support that carries a sample's serialized payload as it is, without decoding
// it (runtime-internal; includes Fast DDS): what the recorder reads and a replay writes.
//
// It registers under one of our IDL type names (e.g. robodds::idl::RobotState) and mirrors that
// type in everything discovery compares: keyed exactly when the real type is (Fast DDS 2.9
// derives the endpoint's topic kind from m_isGetKeyDefined, and EDP refuses to match a keyed
// writer with an unkeyed reader, src/cpp/rtps/builtin/discovery/endpoint/EDP.cpp), and the same
// maximum size (the reader's payload pool).
//
// The key. A Fast DDS 2.9 writer sends an ALIVE sample's key hash only to a reader that expects
// inline QoS (rtps/messages/submessages/DataMsg.hpp); otherwise the reader's history computes
// it by deserialize() + getKey() in the receive thread (DataReaderHistory's
// compute_key_for_change). Our raw readers ask for inline QoS (make them with
// raw_reader_qos()), so getKey() here runs only for a writer that sends no key hash (another
// vendor) and on the writing side (DataWriter::write computes the instance of every sample).
// Then it decodes the payload with the real type support and asks it for the key: the instance
// is exactly the one the typed writer and readers compute (no second copy of the key layout).
// A payload that does not decode gets no key (all-zero handle; a reader computes it itself and
// drops the sample as undecodable); that failed decode is not counted here (it is not a received
// sample: undecodable_samples() stays what readers dropped).

#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace robodds {

/// One sample as raw bytes: the serialized payload with its 4-byte encapsulation header.
struct RawPayload {
  std::vector<std::uint8_t> bytes;
};

class RawPayloadType : public eprosima::fastdds::dds::TopicDataType {
 public:
  /// `type_name`: one of our IDL types (make_type_support); ConfigError if unknown.
  /// `max_size`: 0 = the real type's largest serialized size; more lets a test tool (robodds-fuzz)
  /// write payloads longer than any real sample.
  explicit RawPayloadType(const std::string& type_name, std::uint32_t max_size = 0);
  ~RawPayloadType() override;

  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override;
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override;
  std::function<std::uint32_t()> getSerializedSizeProvider(void* data) override;
  void* createData() override;
  void deleteData(void* data) override;
  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle, bool force_md5) override;

 private:
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> real_;
  std::mutex mutex_;  // getKey() runs in a writing thread and in receive threads
  eprosima::fastrtps::rtps::SerializedPayload_t scratch_;
  void* real_sample_ = nullptr;
};

/// The QoS of a raw reader: `profile`'s, asking writers for the key hash in inline QoS (so the
/// reader's history need not decode each sample to find its instance).
eprosima::fastdds::dds::DataReaderQos raw_reader_qos(const eprosima::fastdds::dds::DataReaderQos& profile_qos);

}  // namespace robodds
