#include "runtime/dds/raw_type.hpp"

#include <cstring>

#include "runtime/base/error.hpp"
#include "runtime/dds/type_support.hpp"

namespace robodds {
namespace rtps = eprosima::fastrtps::rtps;

RawPayloadType::RawPayloadType(const std::string& type_name, std::uint32_t max_size)
    : real_(make_type_support(type_name, false)) {
  if (!real_) {
    throw ConfigError("no type support for type " + type_name + " (not one of the IDL types of idl/robodds.idl)");
  }
  setName(type_name.c_str());
  m_typeSize = std::max(max_size, real_->m_typeSize);
  m_isGetKeyDefined = real_->m_isGetKeyDefined;
  auto_fill_type_object(false);
  auto_fill_type_information(false);
  scratch_.reserve(real_->m_typeSize);
  real_sample_ = real_->createData();
}

RawPayloadType::~RawPayloadType() { real_->deleteData(real_sample_); }

bool RawPayloadType::serialize(void* data, rtps::SerializedPayload_t* payload) {
  const auto& bytes = static_cast<RawPayload*>(data)->bytes;
  if (bytes.size() > payload->max_size) {
    return false;
  }
  if (!bytes.empty()) {
    std::memcpy(payload->data, bytes.data(), bytes.size());
  }
  payload->length = static_cast<std::uint32_t>(bytes.size());
  // What the header says (byte 1 bit 0: little endian); Fast DDS reads it only for its own types.
  payload->encapsulation = bytes.size() >= 2 && (bytes[1] & 1) == 0 ? CDR_BE : CDR_LE;
  return true;
}

bool RawPayloadType::deserialize(rtps::SerializedPayload_t* payload, void* data) {
  auto& bytes = static_cast<RawPayload*>(data)->bytes;
  bytes.assign(payload->data, payload->data + payload->length);
  return true;
}

std::function<std::uint32_t()> RawPayloadType::getSerializedSizeProvider(void* data) {
  const auto size = static_cast<std::uint32_t>(static_cast<RawPayload*>(data)->bytes.size());
  return [size]() { return size; };
}

void* RawPayloadType::createData() { return new RawPayload(); }

void RawPayloadType::deleteData(void* data) { delete static_cast<RawPayload*>(data); }

bool RawPayloadType::getKey(void* data, rtps::InstanceHandle_t* handle, bool force_md5) {
  const auto& bytes = static_cast<RawPayload*>(data)->bytes;
  std::lock_guard<std::mutex> lock(mutex_);
  *handle = rtps::InstanceHandle_t();
  if (bytes.size() > scratch_.max_size) {
    return true;  // longer than any sample of the type: it cannot decode
  }
  if (!bytes.empty()) {
    std::memcpy(scratch_.data, bytes.data(), bytes.size());
  }
  scratch_.length = static_cast<std::uint32_t>(bytes.size());
  scratch_.pos = 0;
  if (!real_->deserialize(&scratch_, real_sample_)) {
    return true;  // no key; a reader drops (and counts) it when it fails to decode it
  }
  return real_->getKey(real_sample_, handle, force_md5);
}

eprosima::fastdds::dds::DataReaderQos raw_reader_qos(const eprosima::fastdds::dds::DataReaderQos& profile_qos) {
  eprosima::fastdds::dds::DataReaderQos qos = profile_qos;
  qos.expects_inline_qos(true);
  return qos;
}

}  // namespace robodds
