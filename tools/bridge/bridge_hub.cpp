#include "tools/bridge/bridge_hub.hpp"

#include <algorithm>

#include "runtime/base/error.hpp"

namespace robodds::bridge {

void BridgeOptions::validate() const {
  if (client_queue_messages < 1 || client_queue_messages > 1000000) {
    throw ConfigError("--client-queue: " + std::to_string(client_queue_messages) + " messages is outside [1, 1000000]");
  }
  if (client_send_buffer_bytes < 1024 || client_send_buffer_bytes > (std::size_t{1} << 30)) {
    throw ConfigError("--client-send-buffer: " + std::to_string(client_send_buffer_bytes) +
                      " bytes is outside [1024, 1073741824]");
  }
  if (client_socket_buffer_bytes != 0 && (client_socket_buffer_bytes < 1024 || client_socket_buffer_bytes > (std::size_t{64} << 20))) {
    throw ConfigError("--client-socket-buffer: " + std::to_string(client_socket_buffer_bytes) +
                      " bytes is outside [1024, 67108864] (0: the system's default)");
  }
  if (client_status_messages < 1) {
    throw ConfigError("client_status_messages must be at least 1");
  }
}

BridgeHub::BridgeHub(BridgeOptions options, std::string server_name, std::vector<std::pair<std::string, std::string>> metadata)
    : options_(options), server_name_(std::move(server_name)), metadata_(std::move(metadata)) {
  options_.validate();
}

std::pair<std::uint32_t, std::vector<BridgeHub::ClientId>> BridgeHub::add_channel(Channel channel) {
  std::lock_guard<std::mutex> lock(mutex_);
  channel.id = next_channel_++;
  channels_.push_back(channel);
  advertised_.insert(channel.id);
  const std::string message = advertise_json({channel});
  std::vector<ClientId> wake;
  for (auto& [id, client] : clients_) {
    client.text.push_back(message);
    if (!client.wake_pending) {
      client.wake_pending = true;
      wake.push_back(id);
    }
  }
  return {channel.id, wake};
}

std::vector<BridgeHub::ClientId> BridgeHub::remove_channel(std::uint32_t channel_id) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<ClientId> wake;
  if (advertised_.erase(channel_id) == 0) {
    return wake;
  }
  channels_.erase(std::remove_if(channels_.begin(), channels_.end(), [&](const Channel& c) { return c.id == channel_id; }),
                  channels_.end());
  const std::string message = unadvertise_json({channel_id});
  for (auto& [id, client] : clients_) {
    for (const std::uint32_t subscription : client.session.drop_channel(channel_id)) {
      client.queue.remove_subscription(subscription);
    }
    client.text.push_back(message);
    if (!client.wake_pending) {
      client.wake_pending = true;
      wake.push_back(id);
    }
  }
  return wake;
}

std::vector<BridgeHub::ClientId> BridgeHub::publish(const std::shared_ptr<const Sample>& sample) {
  std::vector<ClientId> wake;
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& [id, client] : clients_) {
    const std::vector<std::uint32_t>* subscriptions = client.session.subscriptions_of(sample->channel_id);
    if (subscriptions == nullptr) {
      continue;
    }
    for (const std::uint32_t subscription : *subscriptions) {
      client.queue.push(Queued{subscription, sample});
    }
    if (!client.wake_pending) {
      client.wake_pending = true;
      wake.push_back(id);
    }
  }
  return wake;
}

BridgeHub::ClientId BridgeHub::connect(std::string name) {
  std::lock_guard<std::mutex> lock(mutex_);
  const ClientId id = next_client_++;
  Client& client = clients_.emplace(id, Client(options_.client_queue_messages)).first->second;
  client.stats.name = std::move(name);
  client.text.push_back(server_info_json(server_name_, metadata_));
  if (!channels_.empty()) {
    client.text.push_back(advertise_json(channels_));
  }
  return id;
}

ClientStats BridgeHub::disconnect(ClientId client) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = clients_.find(client);
  if (it == clients_.end()) {
    return {};
  }
  ClientStats stats = it->second.stats;
  stats.dropped = it->second.queue.dropped();
  clients_.erase(it);
  return stats;
}

std::vector<std::string> BridgeHub::refuse(Client& client, const std::vector<std::string>& problems) {
  std::vector<std::string> log_lines;
  for (const std::string& problem : problems) {
    ++client.stats.errors;
    if (client.text.size() < options_.client_status_messages) {
      client.text.push_back(status_json(StatusLevel::kError, problem));
    }
    if (client.stats.errors <= options_.logged_errors_per_client) {
      log_lines.push_back(problem);
    }
    if (client.stats.errors == options_.logged_errors_per_client) {
      log_lines.push_back("further bad input from this client is answered with statuses, counted, not logged");
    }
  }
  return log_lines;
}

std::vector<std::string> BridgeHub::on_text(ClientId id, const std::string& text) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = clients_.find(id);
  if (it == clients_.end()) {
    return {};
  }
  Client& client = it->second;
  ClientOp op;
  try {
    op = parse_client_op(text);
  } catch (const ProtocolError& e) {
    // Quote at most 60 bytes of what was sent, so a log line stays one short line.
    const std::string quoted = text.size() > 60 ? text.substr(0, 60) + "..." : text;
    return refuse(client, {"bad message: " + e.message + ": '" + quoted + "'"});
  }
  std::vector<std::uint32_t> removed;
  const std::vector<std::string> problems = client.session.apply(op, advertised_, removed);
  for (const std::uint32_t subscription : removed) {
    client.queue.remove_subscription(subscription);  // nothing of it is sent after the unsubscribe
  }
  return refuse(client, problems);
}

std::vector<std::string> BridgeHub::on_binary(ClientId id, std::size_t size) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = clients_.find(id);
  if (it == clients_.end()) {
    return {};
  }
  return refuse(it->second, {"binary message of " + std::to_string(size) +
                             " bytes ignored: robodds bridge takes no client data (no clientPublish capability)"});
}

std::vector<Outgoing> BridgeHub::take(ClientId id, std::size_t max) {
  std::vector<Outgoing> out;
  std::vector<Queued> data;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = clients_.find(id);
    if (it == clients_.end()) {
      return out;
    }
    Client& client = it->second;
    client.wake_pending = false;
    for (std::string& text : client.text) {
      Outgoing o;
      o.text = std::move(text);
      out.push_back(std::move(o));
    }
    client.text.clear();
    data = client.queue.take(max > out.size() ? max - out.size() : 0);
    client.stats.sent += data.size();
  }
  // Frames are built outside the lock: the DDS threads only wait for the queue operations.
  for (const Queued& q : data) {
    Outgoing o;
    o.binary = true;
    o.frame = message_data_frame(q.subscription_id, q.sample->receive_time_ns, q.sample->payload.data(),
                                 q.sample->payload.size());
    o.receive_steady_ns = q.sample->receive_steady_ns;
    out.push_back(std::move(o));
  }
  return out;
}

std::vector<ClientStats> BridgeHub::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<ClientStats> out;
  for (const auto& [id, client] : clients_) {
    ClientStats s = client.stats;
    s.dropped = client.queue.dropped();
    out.push_back(s);
  }
  return out;
}

}  // namespace robodds::bridge
