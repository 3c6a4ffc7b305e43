#include "tools/bridge/ws_server.hpp"

// Standalone asio, as the server.
#define ASIO_STANDALONE
#include <websocketpp/client.hpp>
#include <websocketpp/config/asio_no_tls_client.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <condition_variable>
#include <mutex>
#include <thread>

#include "runtime/base/error.hpp"

namespace robodds::bridge {
namespace {

using Client = websocketpp::client<websocketpp::config::asio_client>;
using nlohmann::json;
constexpr auto kWait = std::chrono::seconds(10);  // generous: the test machine may be loaded

/// A WebSocket client on the loopback, on a thread of its own.
class TestClient {
 public:
  TestClient(std::uint16_t port, bool foxglove_subprotocol) {
    client_.clear_access_channels(websocketpp::log::alevel::all);
    client_.clear_error_channels(websocketpp::log::elevel::all);
    client_.init_asio();
    client_.set_open_handler([this](websocketpp::connection_hdl) { update([&] { open_ = true; }); });
    client_.set_fail_handler([this](websocketpp::connection_hdl) { update([&] { failed_ = true; }); });
    client_.set_close_handler([this](websocketpp::connection_hdl) { update([&] { closed_ = true; }); });
    client_.set_message_handler([this](websocketpp::connection_hdl, Client::message_ptr m) {
      update([&] {
        (m->get_opcode() == websocketpp::frame::opcode::text ? texts_ : binaries_).push_back(m->get_payload());
      });
    });
    std::error_code ec;
    Client::connection_ptr con = client_.get_connection("ws://127.0.0.1:" + std::to_string(port), ec);
    if (foxglove_subprotocol) {
      con->add_subprotocol(kSubprotocol);
    }
    hdl_ = con->get_handle();
    client_.connect(con);
    thread_ = std::thread([this] { client_.run(); });
  }
  ~TestClient() {
    client_.stop();
    thread_.join();
  }
  template <class Pred>
  bool wait(Pred pred) {
    std::unique_lock<std::mutex> lock(mutex_);
    return cv_.wait_for(lock, kWait, [&] { return pred(*this); });
  }
  void send(const std::string& text) { client_.send(hdl_, text, websocketpp::frame::opcode::text); }
  bool open_ = false, failed_ = false, closed_ = false;
  std::vector<std::string> texts_, binaries_;

 private:
  template <class F>
  void update(F f) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      f();
    }
    cv_.notify_all();
  }
  Client client_;
  websocketpp::connection_hdl hdl_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable cv_;
};

struct Logged {
  std::mutex mutex;
  std::vector<std::string> lines;
  std::function<void(const std::string&)> sink() {
    return [this](const std::string& line) {
      std::lock_guard<std::mutex> lock(mutex);
      lines.push_back(line);
    };
  }
  bool any(const std::string& part) {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& l : lines) {
      if (l.find(part) != std::string::npos) {
        return true;
      }
    }
    return false;
  }
};

TEST(BridgeWsServer, AClientGetsServerInfoAdvertisementsAndItsSubscribedFrames) {
  BridgeHub hub(BridgeOptions{}, "robodds bridge", {});
  Logged log;
  WsServer server(hub, "127.0.0.1", 0, log.sink());  // port 0: any free port
  TestClient client(server.port(), true);
  ASSERT_TRUE(client.wait([](const TestClient& c) { return c.texts_.size() >= 1; })) << "no serverInfo";
  EXPECT_EQ(json::parse(client.texts_[0])["op"], "serverInfo");
  auto [channel, wake] = hub.add_channel(Channel{0, "plant/state", "cdr", "robodds::idl::RobotState", "omgidl", "idl"});
  server.wake(wake);
  ASSERT_TRUE(client.wait([](const TestClient& c) { return c.texts_.size() >= 2; })) << "no advertise";
  EXPECT_EQ(json::parse(client.texts_[1])["channels"][0]["topic"], "plant/state");
  client.send(R"({"op":"subscribe","subscriptions":[{"id":5,"channelId":1}]})");
  client.send("garbage");
  ASSERT_TRUE(client.wait([](const TestClient& c) { return c.texts_.size() >= 3; })) << "no status";
  EXPECT_EQ(json::parse(client.texts_[2])["op"], "status");
  EXPECT_TRUE(log.any("bad message: not JSON"));
  auto sample = std::make_shared<Sample>();
  sample->channel_id = channel;
  sample->receive_time_ns = 42;
  sample->payload = {0, 1, 0, 0, 7};
  server.wake(hub.publish(sample));
  ASSERT_TRUE(client.wait([](const TestClient& c) { return !c.binaries_.empty(); })) << "no Message Data";
  const std::string expected("\x01\x05\x00\x00\x00\x2a\x00\x00\x00\x00\x00\x00\x00\x00\x01\x00\x00\x07", 18);
  EXPECT_EQ(client.binaries_[0], expected);
  const auto start = std::chrono::steady_clock::now();
  const auto still_connected = server.stop(std::chrono::milliseconds(2000));
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(3));
  EXPECT_TRUE(client.wait([](const TestClient& c) { return c.closed_; })) << "the client was not closed";
  EXPECT_TRUE(still_connected.empty());  // it answered the close: its figures are logged
  EXPECT_TRUE(log.any("disconnected: 1 messages sent, 0 dropped"));
  EXPECT_EQ(server.latency().count(), 1u);
}

TEST(BridgeWsServer, AClientWithoutTheFoxgloveSubprotocolIsRefused) {
  BridgeHub hub(BridgeOptions{}, "robodds bridge", {});
  Logged log;
  WsServer server(hub, "127.0.0.1", 0, log.sink());
  TestClient client(server.port(), false);
  ASSERT_TRUE(client.wait([](const TestClient& c) { return c.failed_ || c.open_; }));
  EXPECT_TRUE(client.failed_);
  EXPECT_TRUE(log.any("did not ask for the subprotocol foxglove.websocket.v1"));
}

TEST(BridgeWsServer, ABadAddressOrAPortInUseIsAConfigErrorNamingIt) {
  BridgeHub hub(BridgeOptions{}, "robodds bridge", {});
  try {
    WsServer bad(hub, "localhostt", 0, [](const std::string&) {});
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--address 'localhostt': not an IP address", 0), 0u) << e.what();
  }
  WsServer first(hub, "127.0.0.1", 0, [](const std::string&) {});
  try {
    WsServer second(hub, "127.0.0.1", first.port(), [](const std::string&) {});
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "--address/--port 127.0.0.1:" + std::to_string(first.port()) +
                                         ": cannot listen (Address already in use)");
  }
}

}  // namespace
}  // namespace robodds::bridge
