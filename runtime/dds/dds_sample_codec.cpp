#include "runtime/dds/dds_sample_codec.hpp"

#include <fastcdr/exceptions/Exception.h>
#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "robodds/idl/roboddsPubSubTypes.h"
#include "robodds/idl/robodds_visit.hpp"
#include "runtime/base/error.hpp"

namespace robodds {
namespace {

using eprosima::fastdds::dds::TopicDataType;
using eprosima::fastrtps::rtps::SerializedPayload_t;

/// The generated type support of `type_name` (not the guarded one of make_type_support(): a codec
/// says why bytes do not decode instead of counting them), or nullptr if unknown.
std::shared_ptr<TopicDataType> generated_type(const std::string& type_name) {
  std::shared_ptr<TopicDataType> type;
#define ROBODDS_CODEC_TYPE(T)                                        \
  if (!type && type_name == idl::type_name<idl::T>()) {              \
    type = std::make_shared<idl::T##PubSubType>();                   \
  }
  ROBODDS_FOR_EACH_TOPIC_TYPE(ROBODDS_CODEC_TYPE)
#undef ROBODDS_CODEC_TYPE
  return type;
}

/// A SerializedPayload_t over the caller's buffer instead of one of its own (which it would free).
class BorrowedPayload {
 public:
  explicit BorrowedPayload(std::vector<std::uint8_t>& buffer) {
    payload.data = buffer.data();
    payload.max_size = static_cast<std::uint32_t>(buffer.size());
  }
  ~BorrowedPayload() {
    payload.data = nullptr;  // the buffer's, not the payload's to free
    payload.max_size = 0;
  }
  BorrowedPayload(const BorrowedPayload&) = delete;
  BorrowedPayload& operator=(const BorrowedPayload&) = delete;
  SerializedPayload_t payload;
};

/// What DataWriterImpl does: a payload of the sample's serialized size, then serialize(). Its
/// payload is zero-filled (calloc), so alignment padding is zero: `out` is zeroed likewise.
void serialize_into(TopicDataType& type, const std::string& type_name, const void* sample,
                    std::vector<std::uint8_t>& out) {
  void* data = const_cast<void*>(sample);  // TopicDataType's interface; serialize() only reads it
  out.assign(type.getSerializedSizeProvider(data)(), 0);
  BorrowedPayload borrowed(out);
  if (!type.serialize(data, &borrowed.payload)) {
    throw ConfigError("sample codec: cannot serialize a sample of " + type_name + " (larger than its type's bound)");
  }
  out.resize(borrowed.payload.length);
}

class DdsSampleSerializer : public SampleSerializer {
 public:
  DdsSampleSerializer(std::shared_ptr<TopicDataType> type, std::string type_name)
      : type_(std::move(type)), type_name_(std::move(type_name)) {}
  void serialize(const void* sample, std::vector<std::uint8_t>& out) const override {
    serialize_into(*type_, type_name_, sample, out);
  }

 private:
  std::shared_ptr<TopicDataType> type_;
  std::string type_name_;
};

class DdsSampleCodec : public SampleCodec {
 public:
  std::vector<std::uint8_t> serialize(const std::string& type_name, const void* sample) const override {
    std::vector<std::uint8_t> out;
    serialize_into(*type_of(type_name, "serialize"), type_name, sample, out);
    return out;
  }

  std::unique_ptr<SampleSerializer> serializer(const std::string& type_name) const override {
    return std::make_unique<DdsSampleSerializer>(type_of(type_name, "serialize"), type_name);
  }

  std::shared_ptr<void> deserialize(const std::string& type_name, const std::uint8_t* data,
                                    std::size_t size) const override {
    const std::shared_ptr<TopicDataType> type = type_of(type_name, "deserialize");
    if (size < 4) {
      throw ConfigError("sample codec: cannot decode " + type_name + ": " + std::to_string(size) +
                        " bytes, shorter than the 4-byte encapsulation header");
    }
    if (data[0] != 0x00 || (data[1] != 0x00 && data[1] != 0x01)) {
      throw ConfigError("sample codec: cannot decode " + type_name + ": encapsulation " + hex_byte(data[0]) + " " +
                        hex_byte(data[1]) + " is not XCDR1 (00 00 CDR_BE or 00 01 CDR_LE)");
    }
    SerializedPayload_t payload(static_cast<std::uint32_t>(size));
    std::memcpy(payload.data, data, size);
    payload.length = static_cast<std::uint32_t>(size);
    std::shared_ptr<void> sample(type->createData(), [type](void* p) { type->deleteData(p); });
    bool decoded = false;
    try {
      decoded = type->deserialize(&payload, sample.get());
    } catch (const eprosima::fastcdr::exception::Exception& e) {
      throw ConfigError("sample codec: cannot decode " + type_name + ": " + e.what());
    }
    if (!decoded) {
      throw ConfigError("sample codec: cannot decode " + type_name + ": truncated (" + std::to_string(size) +
                        " bytes, shorter than the type)");
    }
    return sample;
  }

 private:
  static std::string hex_byte(std::uint8_t b) {
    const char* digits = "0123456789abcdef";
    return std::string{digits[b >> 4], digits[b & 0xf]};
  }

  std::shared_ptr<TopicDataType> type_of(const std::string& type_name, const char* what) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = types_.find(type_name);
    if (it == types_.end()) {
      std::shared_ptr<TopicDataType> type = generated_type(type_name);
      if (!type) {
        throw ConfigError(std::string("sample codec: cannot ") + what + " type '" + type_name +
                          "': not one of the IDL topic types (idl/robodds.idl)");
      }
      it = types_.emplace(type_name, std::move(type)).first;
    }
    return it->second;
  }

  mutable std::mutex mutex_;
  mutable std::map<std::string, std::shared_ptr<TopicDataType>> types_;
};

std::mutex& install_mutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

std::shared_ptr<const SampleCodec> make_dds_sample_codec() { return std::make_shared<DdsSampleCodec>(); }

void install_dds_sample_codec() {
  std::lock_guard<std::mutex> lock(install_mutex());
  try {
    sample_codec();  // one installed already (this one, or a test's own): keep it
  } catch (const ConfigError&) {
    set_sample_codec(make_dds_sample_codec());
  }
}

}  // namespace robodds
