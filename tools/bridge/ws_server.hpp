#pragma once
// The WebSocket side of `robodds bridge`: a foxglove.websocket.v1 server (websocketpp on
// standalone asio, one thread of its own) that hands clients' messages to a BridgeHub and sends
// them what the hub has queued. websocketpp and asio stay inside ws_server.cpp.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tools/bridge/bridge_hub.hpp"
#include "tools/bridge/latency_histogram.hpp"

namespace robodds::bridge {

class WsServer {
 public:
  /// Listens on `address`:`port` (port 0: any free one). ConfigError naming --address/--port and
  /// the reason when the address is not an IP address or the port cannot be bound.
  WsServer(BridgeHub& hub, const std::string& address, std::uint16_t port,
           std::function<void(const std::string&)> log_line);
  ~WsServer();
  WsServer(const WsServer&) = delete;
  WsServer& operator=(const WsServer&) = delete;

  /// The port it listens on.
  std::uint16_t port() const;
  /// Thread-safe: sends these clients what the hub queued for them (on the server's thread).
  void wake(const std::vector<BridgeHub::ClientId>& clients);
  /// Closes every connection (going away), waits at most `grace` for the closing handshakes, then
  /// stops the thread. Idempotent. Clients that close log their counts as they go; returns the
  /// counts of those that did not answer the close within `grace`.
  std::vector<ClientStats> stop(std::chrono::milliseconds grace);
  /// Receive (DDS) to send (handed to the socket) latencies of every Message Data frame; read
  /// after stop().
  const LatencyHistogram& latency() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace robodds::bridge
