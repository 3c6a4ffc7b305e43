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
// bookkeeping: only the envelope changes.
//
// Wire format of a batch (never sent to a participant that is not robodds'; see
// BatchingPeers): "RDBT", then per RTPS message a 4-byte little-endian length and the message,
// padded to 4 bytes. A receiver passes anything else through unchanged, and drops the rest of a
// batch whose length or content is inconsistent (counted in malformed_batches()).

#include <fastdds/rtps/transport/TransportDescriptorInterface.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace robodds {

/// Opens a send batch on the calling thread (nestable): until the matching close, the messages
/// this thread sends through a batching transport are held and sent together. Every wait for a
/// peer must come after the close (held messages reach nobody before it).
void open_send_batch();
/// Closes one level; the outermost close sends everything held.
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

/// Batches received that were cut short or held something other than RTPS messages (process-wide).
std::uint64_t malformed_batches();

}  // namespace robodds
