#include "tools/bridge/ws_server.hpp"

// Standalone asio (Debian's libasio-dev), not Boost.Asio.
#define ASIO_STANDALONE
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <thread>

#include "runtime/base/error.hpp"

namespace robodds::bridge {
namespace {

using Server = websocketpp::server<websocketpp::config::asio>;
using Hdl = websocketpp::connection_hdl;

std::int64_t steady_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Messages taken from the hub per round; the send buffer limit is checked between rounds.
constexpr std::size_t kBatch = 64;
// A client that could not take more is retried this often (and on every new sample for it).
constexpr auto kRetryPeriod = std::chrono::milliseconds(20);
// Largest message a client may send (ours are small JSON requests).
constexpr std::size_t kMaxClientMessageBytes = std::size_t{1} << 20;

}  // namespace

struct WsServer::Impl {
  BridgeHub& hub;
  std::function<void(const std::string&)> log_line;
  Server server;
  std::thread thread;
  std::unique_ptr<asio::steady_timer> retry;
  // Touched only on the server's thread, except `open` (read by stop()).
  std::map<BridgeHub::ClientId, Hdl> connections;
  std::map<Hdl, BridgeHub::ClientId, std::owner_less<Hdl>> ids;
  std::atomic<std::size_t> open{0};
  LatencyHistogram latency;
  bool stopped = false;
  std::vector<ClientStats> final_stats;

  Impl(BridgeHub& h, std::function<void(const std::string&)> log) : hub(h), log_line(std::move(log)) {}

  void flush(BridgeHub::ClientId id) {
    const auto it = connections.find(id);
    if (it == connections.end()) {
      return;
    }
    std::error_code ec;
    Server::connection_ptr con = server.get_con_from_hdl(it->second, ec);
    if (ec || con->get_state() != websocketpp::session::state::open) {
      return;
    }
    // What websocketpp holds for the socket and has not written: past the limit the client reads
    // too slowly, and its messages wait in the hub's bounded queue (dropping the oldest) instead.
    while (con->get_buffered_amount() < hub.options().client_send_buffer_bytes) {
      std::vector<Outgoing> batch = hub.take(id, kBatch);
      if (batch.empty()) {
        return;
      }
      for (const Outgoing& o : batch) {
        if (o.binary) {
          ec = con->send(o.frame.data(), o.frame.size(), websocketpp::frame::opcode::binary);
          latency.add(steady_now_ns() - o.receive_steady_ns);
        } else {
          ec = con->send(o.text, websocketpp::frame::opcode::text);
        }
        if (ec) {
          return;  // the connection is closing; its close handler forgets it
        }
      }
    }
  }

  void arm_retry() {
    retry->expires_after(kRetryPeriod);
    retry->async_wait([this](const std::error_code& ec) {
      if (ec || stopped) {
        return;
      }
      for (const auto& [id, hdl] : connections) {
        flush(id);
      }
      arm_retry();
    });
  }

  void forget(Hdl hdl, const std::string& how) {
    const auto it = ids.find(hdl);
    if (it == ids.end()) {
      return;
    }
    const ClientStats s = hub.disconnect(it->second);
    connections.erase(it->second);
    ids.erase(it);
    --open;
    log_line("client " + s.name + " " + how + ": " + std::to_string(s.sent) + " messages sent, " +
             std::to_string(s.dropped) + " dropped (its queue was full), " + std::to_string(s.errors) +
             " bad requests");
  }
};

WsServer::WsServer(BridgeHub& hub, const std::string& address, std::uint16_t port,
                   std::function<void(const std::string&)> log_line)
    : impl_(std::make_unique<Impl>(hub, std::move(log_line))) {
  Impl& s = *impl_;
  std::error_code ec;
  const asio::ip::address ip = asio::ip::make_address(address, ec);
  if (ec) {
    throw ConfigError("--address '" + address + "': not an IP address (" + ec.message() + ")");
  }
  s.server.clear_access_channels(websocketpp::log::alevel::all);
  s.server.clear_error_channels(websocketpp::log::elevel::all);
  s.server.init_asio(ec);
  if (ec) {
    throw RunError("bridge: cannot start asio: " + ec.message());
  }
  s.server.set_reuse_addr(true);
  s.server.set_max_message_size(kMaxClientMessageBytes);
  s.server.set_validate_handler([&s](Hdl hdl) {
    Server::connection_ptr con = s.server.get_con_from_hdl(hdl);
    const std::vector<std::string>& asked = con->get_requested_subprotocols();
    if (std::find(asked.begin(), asked.end(), kSubprotocol) == asked.end()) {
      s.log_line("refused a connection from " + con->get_remote_endpoint() + ": it did not ask for the subprotocol " +
                 kSubprotocol);
      con->set_status(websocketpp::http::status_code::bad_request);
      return false;
    }
    con->select_subprotocol(kSubprotocol);
    return true;
  });
  s.server.set_open_handler([&s](Hdl hdl) {
    Server::connection_ptr con = s.server.get_con_from_hdl(hdl);
    const std::string name = con->get_remote_endpoint();
    if (const std::size_t bytes = s.hub.options().client_socket_buffer_bytes; bytes > 0) {
      std::error_code ignored;  // a refused size leaves the system's: the queue still bounds the client
      con->get_raw_socket().set_option(asio::socket_base::send_buffer_size(static_cast<int>(bytes)), ignored);
    }
    const BridgeHub::ClientId id = s.hub.connect(name);
    s.connections[id] = hdl;
    s.ids[hdl] = id;
    ++s.open;
    s.log_line("client " + name + " connected");
    s.flush(id);
  });
  s.server.set_close_handler([&s](Hdl hdl) { s.forget(hdl, "disconnected"); });
  s.server.set_fail_handler([&s](Hdl hdl) { s.forget(hdl, "failed"); });
  s.server.set_message_handler([&s](Hdl hdl, Server::message_ptr msg) {
    const auto it = s.ids.find(hdl);
    if (it == s.ids.end()) {
      return;
    }
    const std::vector<std::string> lines = msg->get_opcode() == websocketpp::frame::opcode::text
                                               ? s.hub.on_text(it->second, msg->get_payload())
                                               : s.hub.on_binary(it->second, msg->get_payload().size());
    const std::string name = s.server.get_con_from_hdl(hdl)->get_remote_endpoint();
    for (const std::string& line : lines) {
      s.log_line("client " + name + ": " + line);
    }
    s.flush(it->second);
  });
  s.server.listen(asio::ip::tcp::endpoint(ip, port), ec);
  if (ec) {
    throw ConfigError("--address/--port " + address + ":" + std::to_string(port) + ": cannot listen (" + ec.message() + ")");
  }
  s.server.start_accept(ec);
  if (ec) {
    throw RunError("bridge: cannot accept connections: " + ec.message());
  }
  s.retry = std::make_unique<asio::steady_timer>(s.server.get_io_service());
  s.arm_retry();
  s.thread = std::thread([&s] { s.server.run(); });
}

WsServer::~WsServer() { stop(std::chrono::milliseconds(500)); }

std::uint16_t WsServer::port() const {
  std::error_code ec;
  return impl_->server.get_local_endpoint(ec).port();
}

void WsServer::wake(const std::vector<BridgeHub::ClientId>& clients) {
  if (clients.empty()) {
    return;
  }
  asio::post(impl_->server.get_io_service(), [this, clients] {
    for (const BridgeHub::ClientId id : clients) {
      impl_->flush(id);
    }
  });
}

std::vector<ClientStats> WsServer::stop(std::chrono::milliseconds grace) {
  Impl& s = *impl_;
  if (!s.thread.joinable()) {
    return s.final_stats;
  }
  asio::post(s.server.get_io_service(), [&s] {
    s.stopped = true;
    std::error_code ec;
    s.server.stop_listening(ec);
    s.retry->cancel();
    for (const auto& [id, hdl] : s.connections) {
      s.server.close(hdl, websocketpp::close::status::going_away, "robodds bridge stops", ec);
    }
  });
  // A client that stalled cannot answer the close handshake: give up on it after `grace`.
  const auto deadline = std::chrono::steady_clock::now() + grace;
  while (s.open > 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // The clients that closed have logged their figures (forget()); these did not answer in time.
  s.final_stats = s.hub.stats();
  s.server.stop();  // io_service::stop(): run() returns at once
  s.thread.join();
  return s.final_stats;
}

const LatencyHistogram& WsServer::latency() const { return impl_->latency; }

}  // namespace robodds::bridge
