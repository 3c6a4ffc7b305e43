// `robodds bridge`: a Foxglove WebSocket protocol server (foxglove.websocket.v1) that streams the
// topics seen on a domain, like foxglove_bridge for ROS 2. Each topic is advertised when its first
// sample arrives (unadvertised when its last writer goes), as the channel a recording would have
// (schema encoding omgidl with the IDL text, message encoding cdr), and a subscribed client gets the
// samples' payloads exactly as on the wire.
//
// The DDS callbacks only hand a shared copy of the bytes to the clients' bounded queues
// (tools/bridge/bridge_hub.hpp); the server's thread sends them. A slow or stalled client loses its
// oldest messages (counted) and never holds a DDS receive thread.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "idl/idl_schema.hpp"
#include "runtime/base/error.hpp"
#include "runtime/base/log.hpp"
#include "runtime/dds/raw_bus.hpp"
#include "runtime/launch/launch.hpp"
#include "runtime/topics/topic_catalog.hpp"
#include "tools/bridge/bridge_hub.hpp"
#include "tools/bridge/ws_server.hpp"
#include "system/foxglove/robot_poses.hpp"
#include "tools/robodds/catalog_topics.hpp"
#include "tools/robodds/command.hpp"
#include "tools/robodds/scene_source.hpp"

namespace robodds {
namespace {

std::int64_t steady_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

class BridgeCommand : public Command {
 public:
  BridgeCommand(CLI::App& app, const CommandEnv& env) : env_(env) {
    cmd_ = app.add_subcommand("bridge", "live view: a Foxglove WebSocket server streaming the topics of the domain (like foxglove_bridge)");
    cmd_->add_option("--topics", topics_, "topic names to offer, e.g. plant/state sensor/position (default: --all)");
    cmd_->add_flag("--all", all_, "offer every topic of the topic catalog (the default)");
    cmd_->add_option("--address", address_, "IP address to listen on (0.0.0.0: every interface)");
    cmd_->add_option("--port", port_, "TCP port to listen on (0: any free port, printed)")->check(CLI::Range(0, 65535));
    cmd_->add_option("--duration", duration_s_, "s of wall-clock time to serve (0 = until Ctrl-C / SIGTERM)")
        ->check(CLI::Range(0.0, 1e9));
    cmd_->add_option("--client-queue", options_.client_queue_messages,
                     "messages waiting per client; a client that reads slower loses its oldest ones (counted)");
    cmd_->add_option("--client-send-buffer", options_.client_send_buffer_bytes,
                     "bytes handed to a client's socket and not yet written before messages wait in its queue");
    cmd_->add_option("--client-socket-buffer", options_.client_socket_buffer_bytes,
                     "SO_SNDBUF of each client's socket in bytes (0: the system's default)");
    cmd_->add_flag("--foxglove-scene", foxglove_scene_,
                   "also offer foxglove/robot_poses: every robot's pose from plant/state as a foxglove.PosesInFrame "
                   "(JSON), which Foxglove's 3D panel draws without configuration");
    add_dds_options(cmd_, dds_);
  }

  bool parsed() const override { return cmd_->parsed(); }

  int run() override {
    options_.validate();
    const std::vector<const TopicInfo*> topics = chosen_topics();
    const DdsOptions dds = tools_dds(dds_, "robodds-bridge");  // the `tools` identity: reads every topic
    const int domain = dds.domain_id;
    bridge::BridgeHub hub(options_, "robodds bridge", {{"domain", std::to_string(domain)}});
    const auto log_line = [](const std::string& line) { log::info("bridge", line); };
    // The socket first: a port in use fails before anything joins the domain.
    bridge::WsServer server(hub, address_, static_cast<std::uint16_t>(port_), log_line);

    // --foxglove-scene: the derived channel (0 until plant/state's first sample) and the scene, sent
    // at most once per foxglove::kScenePeriodNs of the samples' stamps (SceneFeed): 200 robots at
    // 100 Hz would otherwise be 20,000 messages/s of 200 poses each to every subscribed client.
    if (foxglove_scene_) {
      require_scene_source(topics, "--topics");
    }
    std::mutex scene_mutex;
    std::uint32_t scene_channel = 0;
    SceneFeed scene("bridge");
    const auto publish_scene = [&](const RawSample& s, std::int64_t received) {
      std::lock_guard<std::mutex> lock(scene_mutex);
      const std::optional<std::string> text = scene.take(s.data, s.size, s.source_time_ns);
      if (!text) {
        return;
      }
      if (scene_channel == 0) {
        auto [id, wake] = hub.add_channel(bridge::Channel{0, foxglove::kRobotPosesTopic, "json", foxglove::kPosesInFrameSchemaName,
                                                          "jsonschema", foxglove::poses_in_frame_json_schema()});
        scene_channel = id;
        server.wake(wake);
      }
      auto sample = std::make_shared<bridge::Sample>();
      sample->channel_id = scene_channel;
      sample->receive_time_ns = static_cast<std::uint64_t>(s.reception_time_ns);
      sample->receive_steady_ns = received;
      sample->payload.assign(text->begin(), text->end());
      server.wake(hub.publish(sample));
    };

    // Channel id of each topic, 0 until its first sample advertises it.
    std::vector<std::atomic<std::uint32_t>> channel_of(topics.size());
    std::mutex advertise_mutex;
    auto bus = make_raw_bus(dds);
    for (std::size_t i = 0; i < topics.size(); ++i) {
      const TopicInfo& topic = *topics[i];
      bus->reader(topic.name, topic.type_name, monitor_profile_for(topic),
                  [&, i](const RawSample& s) {
                    const std::int64_t received = steady_now_ns();
                    std::uint32_t channel = channel_of[i].load();
                    if (channel == 0) {
                      std::lock_guard<std::mutex> lock(advertise_mutex);
                      channel = channel_of[i].load();
                      if (channel == 0) {
                        const TopicInfo& t = *topics[i];
                        auto [id, wake] = hub.add_channel(bridge::Channel{0, t.name, "cdr", idl_schema_name(t.type_name),
                                                                          "omgidl", idl_schema_text(t.type_name)});
                        channel_of[i] = channel = id;
                        server.wake(wake);
                      }
                    }
                    auto sample = std::make_shared<bridge::Sample>();
                    sample->channel_id = channel;
                    sample->receive_time_ns = static_cast<std::uint64_t>(s.reception_time_ns);
                    sample->receive_steady_ns = received;
                    sample->payload.assign(s.data, s.data + s.size);
                    server.wake(hub.publish(sample));
                    if (foxglove_scene_ && topics[i]->name == kSceneSource) {
                      publish_scene(s, received);
                    }
                  },
                  [name = topic.name](const std::string& e) { log::warn("bridge", name + ": " + e); });
      // The topic's last writer gone: unadvertise it (a later writer's first sample advertises it anew).
      bus->watch_writers(topic.name, [&, i](int writers) {
        if (writers > 0) {
          return;
        }
        std::lock_guard<std::mutex> lock(advertise_mutex);
        if (const std::uint32_t channel = channel_of[i].exchange(0); channel != 0) {
          server.wake(hub.remove_channel(channel));
        }
        if (topics[i]->name == kSceneSource) {  // the scene goes with its source
          std::lock_guard<std::mutex> scene_lock(scene_mutex);
          if (scene_channel != 0) {
            server.wake(hub.remove_channel(scene_channel));
            scene_channel = 0;
          }
          // A next run starts afresh: its robots only, its stamps (a lockstep run's restart at 0)
          // due at once.
          scene = SceneFeed("bridge");
        }
      });
    }
    bus->start();
    std::printf("robodds bridge: %zu topics of domain %d on ws://%s:%u (foxglove.websocket.v1)\n", topics.size(), domain,
                address_.c_str(), static_cast<unsigned>(server.port()));
    std::fflush(stdout);

    const auto start = std::chrono::steady_clock::now();
    while (!env_.stop &&
           (duration_s_ <= 0 || std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < duration_s_)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    bus->close_readers();  // no callback runs after this
    // Clients that stalled cannot answer the closing handshake: 1 s at most for them (their
    // figures are printed here; the others log theirs as they close).
    for (const bridge::ClientStats& s : server.stop(std::chrono::milliseconds(1000))) {
      std::printf("robodds bridge: client %s did not answer the close: %llu messages sent, %llu dropped (its queue was full), %llu bad requests\n",
                  s.name.c_str(), static_cast<unsigned long long>(s.sent), static_cast<unsigned long long>(s.dropped),
                  static_cast<unsigned long long>(s.errors));
    }
    std::printf("robodds bridge: receive->send latency: %s\n", server.latency().summary().c_str());
    return 0;
  }

 private:
  std::vector<const TopicInfo*> chosen_topics() const {
    if (all_ && !topics_.empty()) {
      throw ConfigError("--topics and --all: give one of them (neither: --all)");
    }
    return catalog_topics(topics_, "--topics");
  }

  const CommandEnv& env_;
  CLI::App* cmd_ = nullptr;
  std::vector<std::string> topics_;
  bool all_ = false;
  std::string address_ = "127.0.0.1";  // loopback only unless asked: the bridge has no authentication
  int port_ = 8765;                    // foxglove_bridge's default
  double duration_s_ = 0.0;
  bool foxglove_scene_ = false;
  bridge::BridgeOptions options_;
  DdsArgs dds_;
};

}  // namespace

std::unique_ptr<Command> add_bridge_command(CLI::App& app, const CommandEnv& env) {
  return std::make_unique<BridgeCommand>(app, env);
}

}  // namespace robodds
