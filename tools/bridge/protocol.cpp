#include "tools/bridge/protocol.hpp"

#include <limits>

#include <nlohmann/json.hpp>

namespace robodds::bridge {
namespace {

using nlohmann::json;

std::uint32_t u32_field(const json& object, const char* key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) {
    throw ProtocolError(where + ": missing \"" + key + "\"");
  }
  if (!it->is_number_integer() || it->get<std::int64_t>() < 0 ||
      it->get<std::int64_t>() > std::numeric_limits<std::uint32_t>::max()) {
    throw ProtocolError(where + ": \"" + key + "\" is " + it->dump() + ", not an unsigned 32-bit integer");
  }
  return static_cast<std::uint32_t>(it->get<std::int64_t>());
}

const json& array_field(const json& object, const char* key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_array()) {
    throw ProtocolError(where + ": \"" + key + "\" must be an array");
  }
  return *it;
}

}  // namespace

std::string server_info_json(const std::string& name, const std::vector<std::pair<std::string, std::string>>& metadata) {
  json meta = json::object();
  for (const auto& [k, v] : metadata) {
    meta[k] = v;
  }
  // No capabilities: the bridge only streams (no client publish, parameters, services, time).
  return json{{"op", "serverInfo"}, {"name", name}, {"capabilities", json::array()},
              {"supportedEncodings", json::array()}, {"metadata", meta}}
      .dump();
}

std::string advertise_json(const std::vector<Channel>& channels) {
  json list = json::array();
  for (const Channel& c : channels) {
    list.push_back({{"id", c.id}, {"topic", c.topic}, {"encoding", c.encoding}, {"schemaName", c.schema_name},
                    {"schemaEncoding", c.schema_encoding}, {"schema", c.schema}});
  }
  return json{{"op", "advertise"}, {"channels", list}}.dump();
}

std::string unadvertise_json(const std::vector<std::uint32_t>& channel_ids) {
  return json{{"op", "unadvertise"}, {"channelIds", channel_ids}}.dump();
}

std::string status_json(StatusLevel level, const std::string& message) {
  // Invalid UTF-8 from a client's text (quoted back in a message) is replaced, not thrown.
  return json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}.dump(
      -1, ' ', false, json::error_handler_t::replace);
}

ClientOp parse_client_op(const std::string& text) {
  json message;
  try {
    message = json::parse(text);
  } catch (const json::parse_error& e) {
    // nlohmann's what() is "[json.exception.parse_error.101] parse error at line 1, column 2: ...".
    std::string reason = e.what();
    const auto colon = reason.find("] ");
    throw ProtocolError("not JSON (" + (colon == std::string::npos ? reason : reason.substr(colon + 2)) + ")");
  }
  if (!message.is_object()) {
    throw ProtocolError("not a JSON object");
  }
  const auto op = message.find("op");
  if (op == message.end() || !op->is_string()) {
    throw ProtocolError("no string \"op\"");
  }
  ClientOp out;
  out.op = op->get<std::string>();
  if (out.op == "subscribe") {
    out.kind = ClientOp::Kind::kSubscribe;
    for (const json& s : array_field(message, "subscriptions", "subscribe")) {
      if (!s.is_object()) {
        throw ProtocolError("subscribe: each subscription must be an object {\"id\", \"channelId\"}");
      }
      out.subscribe.emplace_back(u32_field(s, "id", "subscribe"), u32_field(s, "channelId", "subscribe"));
    }
  } else if (out.op == "unsubscribe") {
    out.kind = ClientOp::Kind::kUnsubscribe;
    for (const json& id : array_field(message, "subscriptionIds", "unsubscribe")) {
      if (!id.is_number_integer() || id.get<std::int64_t>() < 0 ||
          id.get<std::int64_t>() > std::numeric_limits<std::uint32_t>::max()) {
        throw ProtocolError("unsubscribe: subscription id " + id.dump() + " is not an unsigned 32-bit integer");
      }
      out.unsubscribe.push_back(static_cast<std::uint32_t>(id.get<std::int64_t>()));
    }
  }
  return out;
}

std::vector<std::uint8_t> message_data_frame(std::uint32_t subscription_id, std::uint64_t receive_time_ns,
                                             const std::uint8_t* payload, std::size_t size) {
  std::vector<std::uint8_t> frame(kMessageDataHeaderBytes + size);
  frame[0] = 0x01;
  for (int i = 0; i < 4; ++i) {
    frame[1 + i] = static_cast<std::uint8_t>(subscription_id >> (8 * i));
  }
  for (int i = 0; i < 8; ++i) {
    frame[5 + i] = static_cast<std::uint8_t>(receive_time_ns >> (8 * i));
  }
  std::copy(payload, payload + size, frame.begin() + kMessageDataHeaderBytes);
  return frame;
}

}  // namespace robodds::bridge
