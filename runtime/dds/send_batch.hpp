#pragma once
// Send batching (runtime-internal; includes Fast DDS): the RTPS messages one thread sends while a
// batch is open on it (open_send_batch()) leave as one transport message per sender resource and
// destination list, and are split again by the receiving participant's transport.
//
// Why: Fast DDS 2.9 publishing synchronously sends every sample as its own RTPS message: one
// shared-memory (or UDP) message per sample and reader participant, and, when the receiving thread
// sleeps, one wake-up each. A lockstep host writes every robot's sample of a step in one burst
// (200 robots: ~400 messages per step and host). Fast DDS' own grouping (asynchronous publication)
// wakes its thread per sample and measured slower (docs/performance.md). Batching below Fast DDS,
// in a transport that wraps the shared-memory and UDPv4 transports (ChainingTransport), keeps
// every sample a keyed RTPS DATA submessage of its own writer, sequence number and reliability
// bookkeeping: only the envelope changes (docs/performance.md, "Batched sends").
//
// Only robodds participants can split a batch: a message is held only when every destination
// locator belongs to a participant that announced robodds components (BatchingPeers, filled by
// the participant listener from discovery); anything else (a plain Fast DDS or ROS 2 participant,
// a multicast locator, an unknown one) gets its message at once, after what the same sender held.
//
// Wire format of a batch: "RDBT", then per RTPS message a 4-byte little-endian length and the
// message, padded to 4 bytes, then a zero length and kTrailerBytes zero bytes (send_batch.cpp says
// why); a message held alone leaves as it is. A receiver passes anything not starting with "RDBT"
// through unchanged, and drops the rest of a batch whose length or content is inconsistent (counted
// in send_batch_counters(), logged once).

#include <fastdds/rtps/common/Locator.h>
#include <fastdds/rtps/transport/TransportDescriptorInterface.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace robodds {

/// Opens a send batch on the calling thread (nestable): until the matching close, the messages
/// this thread sends through a batching transport to robodds participants are held and sent
/// together. Every wait for a peer must come after the close (held messages reach nobody before it).
void open_send_batch();
/// Closes one level; the outermost close sends everything held (through transports still alive).
void close_send_batch();

/// RAII form of open_send_batch()/close_send_batch().
class SendBatchScope {
 public:
  SendBatchScope() { open_send_batch(); }
  ~SendBatchScope() { close_send_batch(); }
  SendBatchScope(const SendBatchScope&) = delete;
  SendBatchScope& operator=(const SendBatchScope&) = delete;
};

/// The transports of a participant's QoS with their batching versions: every shared-memory and
/// UDPv4 descriptor is replaced by one that batches (same settings); other kinds are kept.
std::vector<std::shared_ptr<eprosima::fastdds::rtps::TransportDescriptorInterface>> batching_transports(
    const std::vector<std::shared_ptr<eprosima::fastdds::rtps::TransportDescriptorInterface>>& transports);

/// One participant listener's entries in the process-wide registry of the locators of robodds
/// participants (those a batch may go to). Each discovered robodds participant's unicast locators
/// are registered while it is alive; a locator counts as long as any BatchingPeers of the process
/// registers it (two local participants discover the same peer). Not thread-safe: the owner
/// serialises its calls (PeerDirectory: under its mutex). The destructor unregisters everything.
class BatchingPeers {
 public:
  BatchingPeers() = default;
  ~BatchingPeers();
  BatchingPeers(const BatchingPeers&) = delete;
  BatchingPeers& operator=(const BatchingPeers&) = delete;

  /// `participant` (any key naming a remote participant, e.g. its GUID prefix) is a robodds
  /// participant reached at `locators`: replaces what was registered for it.
  void set(const std::string& participant, std::vector<eprosima::fastrtps::rtps::Locator_t> locators);
  /// Unregisters `participant`'s locators (it left or was dropped, or announces nothing any more).
  void erase(const std::string& participant);

 private:
  std::map<std::string, std::vector<eprosima::fastrtps::rtps::Locator_t>> registered_;
};

/// Process-wide counts, for tests and the debug line logged at a participant's deletion.
struct SendBatchCounters {
  std::uint64_t batches_sent = 0;       // transport messages that carried a batch (of two messages or more)
  std::uint64_t messages_batched = 0;   // RTPS messages sent inside them (a message held alone leaves as it is)
  std::uint64_t messages_not_held = 0;  // sent at once inside a batch (a destination that is no robodds participant's, too big)
  std::uint64_t malformed_received = 0; // received batches cut short or holding other than RTPS messages
};
SendBatchCounters send_batch_counters();

namespace detail {

/// What split_batch() found in a received buffer.
enum class BatchSplit { kNotABatch, kWhole, kMalformed };

/// Hands each RTPS message of the batch in `buffer` to `deliver` in order, up to the end marker or
/// the first inconsistency (a length beyond the buffer, a message not starting with "RTPS", no end
/// marker): kMalformed then, with what came before delivered. kNotABatch (nothing delivered) when
/// `buffer` does not start with "RDBT". Never reads outside [buffer, buffer + size).
BatchSplit split_batch(const std::uint8_t* buffer, std::size_t size,
                       const std::function<void(const std::uint8_t* message, std::uint32_t length)>& deliver);

/// Whether every one of `locators` is registered by some BatchingPeers (false for an empty list).
bool all_batching_peers(const std::vector<eprosima::fastrtps::rtps::Locator_t>& locators);

}  // namespace detail
}  // namespace robodds
