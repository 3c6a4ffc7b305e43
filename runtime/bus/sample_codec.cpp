#include "runtime/bus/sample_codec.hpp"

#include <mutex>
#include <utility>

#include "runtime/base/error.hpp"

namespace robodds {
namespace {

struct Installed {
  std::mutex mutex;
  std::shared_ptr<const SampleCodec> codec;
};

Installed& installed() {
  static Installed slot;
  return slot;
}

class ByNameSerializer : public SampleSerializer {
 public:
  ByNameSerializer(const SampleCodec& codec, std::string type_name) : codec_(codec), type_name_(std::move(type_name)) {}
  void serialize(const void* sample, std::vector<std::uint8_t>& out) const override {
    const std::vector<std::uint8_t> bytes = codec_.serialize(type_name_, sample);
    out.assign(bytes.begin(), bytes.end());
  }

 private:
  const SampleCodec& codec_;
  std::string type_name_;
};

}  // namespace

std::unique_ptr<SampleSerializer> SampleCodec::serializer(const std::string& type_name) const {
  return std::make_unique<ByNameSerializer>(*this, type_name);
}

const SampleCodec& sample_codec() {
  Installed& slot = installed();
  std::lock_guard<std::mutex> lock(slot.mutex);
  if (!slot.codec) {
    throw ConfigError("no sample codec installed (runtime/dds installs it when DDS is set up: install_dds_sample_codec())");
  }
  return *slot.codec;
}

void set_sample_codec(std::shared_ptr<const SampleCodec> codec) {
  Installed& slot = installed();
  std::lock_guard<std::mutex> lock(slot.mutex);
  slot.codec = std::move(codec);
}

}  // namespace robodds
