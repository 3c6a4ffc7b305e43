#pragma once
// The messages waiting for one WebSocket client, bounded: a slow client never makes the bridge
// (or, through it, a DDS receive thread) wait or grow without limit. When the queue is full the
// oldest message is dropped (a live view wants the newest data) and counted.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

namespace robodds::bridge {

/// One received sample, shared by every client that is subscribed to its channel.
struct Sample {
  std::uint32_t channel_id = 0;
  std::uint64_t receive_time_ns = 0;    // when the bridge's reader got it, ns since the epoch (sent to the client)
  std::int64_t receive_steady_ns = 0;   // the same moment on the monotonic clock (for the latency figures)
  std::vector<std::uint8_t> payload;    // the serialized sample as on the wire
};

struct Queued {
  std::uint32_t subscription_id = 0;
  std::shared_ptr<const Sample> sample;
};

class ClientQueue {
 public:
  /// `capacity` >= 1 messages.
  explicit ClientQueue(std::size_t capacity);

  /// Appends; when full, drops the oldest first. True if nothing was dropped.
  bool push(Queued message);
  /// Up to `max` messages, oldest first.
  std::vector<Queued> take(std::size_t max);
  /// Removes every message of `subscription_id` (after an unsubscribe: nothing more of it is sent).
  void remove_subscription(std::uint32_t subscription_id);

  std::size_t size() const { return queue_.size(); }
  std::uint64_t dropped() const { return dropped_; }

 private:
  std::size_t capacity_;
  std::deque<Queued> queue_;
  std::uint64_t dropped_ = 0;
};

}  // namespace robodds::bridge
