#pragma once
// Samples as bytes without the transport: what a recorder writes to a file and a replay reads
// back. This header stays free of Fast DDS: runtime/dds implements it with the type support a
// DDS writer uses (runtime/dds/dds_sample_codec.hpp) and installs it where DDS is set up.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace robodds {

/// Serializes samples of one type (SampleCodec::serializer()): SampleCodec::serialize()'s bytes
/// into a buffer the caller keeps, so a recorder writing millions of samples neither looks the
/// type up by name nor allocates per sample. One serializer is used by one thread at a time.
class SampleSerializer {
 public:
  virtual ~SampleSerializer() = default;
  /// Replaces `out` with the sample's payload (exactly SampleCodec::serialize()'s bytes); `out`
  /// keeps its capacity, so reusing it allocates only for a sample larger than any before.
  virtual void serialize(const void* sample, std::vector<std::uint8_t>& out) const = 0;
};

class SampleCodec {
 public:
  virtual ~SampleCodec() = default;
  /// The sample's serialized payload exactly as a Fast DDS writer of our type support puts it on
  /// the wire: 4-byte encapsulation header + XCDR1 body (alignment padding zero, so the same
  /// sample always gives the same bytes). ConfigError naming the type if unknown.
  virtual std::vector<std::uint8_t> serialize(const std::string& type_name, const void* sample) const = 0;
  /// A serializer of `type_name`'s samples; ConfigError naming the type if unknown. Default: one
  /// that calls serialize() (a codec without a faster path, e.g. a test's).
  virtual std::unique_ptr<SampleSerializer> serializer(const std::string& type_name) const;
  /// A new sample of `type_name` decoded from such bytes; ConfigError naming the type and why
  /// (unknown type, bad encapsulation, truncated) when they do not decode.
  virtual std::shared_ptr<void> deserialize(const std::string& type_name, const std::uint8_t* data,
                                            std::size_t size) const = 0;
};

/// The program's codec (installed by runtime/dds where make_dds_bus / make_raw_bus set up DDS,
/// and by the launcher before the producer check's dry configure, before any run starts; or by a
/// test); ConfigError "no sample codec installed" otherwise. The
/// reference stays valid until the next set_sample_codec().
const SampleCodec& sample_codec();
void set_sample_codec(std::shared_ptr<const SampleCodec> codec);

}  // namespace robodds
