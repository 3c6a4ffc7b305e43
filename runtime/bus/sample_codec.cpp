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

}  // namespace

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
