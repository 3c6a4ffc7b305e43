#pragma once
// Raw DDS access by topic and type name: samples as their serialized bytes, never decoded (what
// `robodds record` reads and a replay writes). This header stays free of Fast DDS includes.

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "runtime/bus/bus.hpp"
#include "runtime/dds/dds_bus.hpp"

namespace robodds {

/// One received sample.
struct RawSample {
  const std::uint8_t* data = nullptr;  // the serialized payload exactly as on the wire, with its
  std::size_t size = 0;                // 4-byte encapsulation header (XCDR1 for our types)
  std::int64_t source_time_ns = 0;     // the writer's source timestamp, ns since the epoch
  std::int64_t reception_time_ns = 0;  // when this participant received it, ns since the epoch
  std::array<std::uint8_t, 16> writer_guid{};  // the writing DataWriter: GUID prefix + entity id
  std::array<std::uint8_t, 16> instance{};     // the DDS instance (key hash); all zero: unkeyed topic
};

/// Called for each received sample, from a Fast DDS thread, one call at a time per topic; the
/// bytes are valid only during the call.
using RawSampleCallback = std::function<void(const RawSample& sample)>;

/// Called with the number of writers matched to a reader each time it changes (a writer found,
/// or lost: deleted, or its participant gone), from a Fast DDS thread.
using RawWritersCallback = std::function<void(int matched_writers)>;

class RawWriter {
 public:
  virtual ~RawWriter() = default;
  /// Publishes `size` bytes (a serialized payload with its encapsulation header) as one sample;
  /// its instance is the one the real type computes from them. False if DDS refused it.
  virtual bool write(const std::uint8_t* data, std::size_t size) = 0;
  /// Readers matched now.
  virtual int matched_readers() const = 0;
  /// Waits (at most `timeout`) until every matched reliable reader has acknowledged every sample.
  virtual bool wait_acknowledged(std::chrono::milliseconds timeout) = 0;
};

class RawBus {
 public:
  virtual ~RawBus() = default;
  /// Reads `topic` as `type_name` (one of our IDL types) with QoS profile `profile`. Readers are
  /// created at start(). ConfigError for an unknown type, a second reader of the same topic, or a
  /// reader Fast DDS refuses (at start()).
  virtual void reader(const std::string& topic, const std::string& type_name, const std::string& profile,
                      RawSampleCallback on_sample, ReaderEventCallback on_event) = 0;
  /// Calls `on_writers` whenever the number of writers matched to `topic`'s reader changes; after
  /// reader(), before start() (ConfigError otherwise).
  virtual void watch_writers(const std::string& topic, RawWritersCallback on_writers) = 0;
  virtual void start() = 0;
  /// Deletes every reader: no callback runs once it returns.
  virtual void close_readers() = 0;
  /// A writer of `topic` as `type_name` with QoS profile `profile`, keeping at least
  /// `min_history_depth` samples per instance (0: the profile's depth). A replay needs more than a
  /// command profile's depth 1: under load a sample not yet sent or acknowledged would be replaced
  /// by the next one of its instance and never reach a recorder. History is the writer's own and
  /// takes no part in matching. ConfigError if refused.
  virtual std::shared_ptr<RawWriter> writer(const std::string& topic, const std::string& type_name, const std::string& profile,
                                            std::int32_t min_history_depth) = 0;
};

/// One DomainParticipant of its own (options as for make_dds_bus: QoS files, profile, security,
/// discovery servers); ConfigError naming a bad QoS file or profile, RunError if DDS fails.
std::unique_ptr<RawBus> make_raw_bus(const DdsOptions& options);

}  // namespace robodds
