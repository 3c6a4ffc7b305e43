#pragma once
// The bridge between the DDS side and the WebSocket clients, without sockets: the advertised
// channels, each client's subscriptions, its bounded queue of messages and its counts. Thread-safe:
// DDS receive threads call publish() and add_channel(), the server's thread the rest. Nothing here
// waits for a client: publish() only appends to queues (dropping a slow client's oldest message).

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "tools/bridge/client_queue.hpp"
#include "tools/bridge/client_session.hpp"
#include "tools/bridge/protocol.hpp"

namespace robodds::bridge {

struct BridgeOptions {
  /// Messages waiting per client. At 100 Hz on ~20 topics, 1000 is ~0.5 s of data: a client that
  /// falls further behind loses its oldest messages (counted) instead of holding the bridge.
  std::size_t client_queue_messages = 1000;
  /// Bytes handed to a client's socket and not yet written; past it, messages wait in the queue.
  std::size_t client_send_buffer_bytes = std::size_t{1} << 20;
  /// SO_SNDBUF of each client's socket (bytes; 0: the system's, which Linux grows up to 4 MiB).
  /// Smaller: a stalled client holds less kernel memory and its drops start sooner.
  std::size_t client_socket_buffer_bytes = 0;
  /// Status messages waiting per client (answers to bad input); more are dropped, counted.
  std::size_t client_status_messages = 100;
  /// Bad-input log lines per client; later ones are counted, not logged.
  std::size_t logged_errors_per_client = 20;
  /// ConfigError naming the option (as --option) when a value is out of range.
  void validate() const;
};

/// What a client is sent next: a text message or a Message Data frame.
struct Outgoing {
  bool binary = false;
  std::string text;
  std::vector<std::uint8_t> frame;
  std::int64_t receive_steady_ns = 0;  // binary: when the sample was received (monotonic ns)
};

struct ClientStats {
  std::string name;
  std::uint64_t sent = 0;     // Message Data frames taken for sending
  std::uint64_t dropped = 0;  // Message Data dropped: its queue was full
  std::uint64_t errors = 0;   // bad input answered with an error status
};

class BridgeHub {
 public:
  using ClientId = std::uint64_t;

  BridgeHub(BridgeOptions options, std::string server_name, std::vector<std::pair<std::string, std::string>> metadata);

  /// Adds and advertises a channel (its id is set here, from 1); returns it and the clients to
  /// wake (each has the advertisement queued).
  std::pair<std::uint32_t, std::vector<ClientId>> add_channel(Channel channel);
  /// Unadvertises a channel (its topic's last writer went): every client is told, its
  /// subscriptions of it and their queued messages are dropped. Returns the clients to wake. The
  /// id is never used again: the topic's next sample advertises a new channel.
  std::vector<ClientId> remove_channel(std::uint32_t channel_id);
  /// Queues `sample` for every client subscribed to its channel; returns the clients that had no
  /// wake-up pending (the caller wakes them).
  std::vector<ClientId> publish(const std::shared_ptr<const Sample>& sample);

  /// A new client: serverInfo and the advertisement of every channel are queued for it.
  ClientId connect(std::string name);
  /// Forgets the client and its subscriptions; returns its counts.
  ClientStats disconnect(ClientId client);
  /// A client's text message: subscribe/unsubscribe applied, an error status queued per problem.
  /// Returns the lines to log (at most logged_errors_per_client per client, then one saying so).
  std::vector<std::string> on_text(ClientId client, const std::string& text);
  /// A client's binary message: the bridge takes none (no clientPublish capability).
  std::vector<std::string> on_binary(ClientId client, std::size_t size);
  /// Up to `max` messages for the client, text first; clears its pending wake-up.
  std::vector<Outgoing> take(ClientId client, std::size_t max);

  std::vector<ClientStats> stats() const;
  const BridgeOptions& options() const { return options_; }

 private:
  struct Client {
    ClientStats stats;
    ClientSession session;
    ClientQueue queue;
    std::vector<std::string> text;  // control messages, sent before data
    bool wake_pending = false;
    explicit Client(std::size_t capacity) : queue(capacity) {}
  };
  std::vector<std::string> refuse(Client& client, const std::vector<std::string>& problems);

  const BridgeOptions options_;
  const std::string server_name_;
  const std::vector<std::pair<std::string, std::string>> metadata_;
  mutable std::mutex mutex_;
  std::vector<Channel> channels_;  // advertised now
  std::uint32_t next_channel_ = 1;
  std::set<std::uint32_t> advertised_;
  std::map<ClientId, Client> clients_;
  ClientId next_client_ = 1;
};

}  // namespace robodds::bridge
