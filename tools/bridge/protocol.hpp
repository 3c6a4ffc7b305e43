#pragma once
// The Foxglove WebSocket protocol (foxglove.websocket.v1, github.com/foxglove/ws-protocol), the
// server side robodds needs: the JSON text messages it sends (serverInfo, advertise, unadvertise,
// status), the client operations it understands (subscribe, unsubscribe) and the binary Message
// Data frame. Plain C++ (nlohmann::json), no sockets.

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace robodds::bridge {

/// The WebSocket subprotocol a client must ask for.
inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

/// One advertised channel.
struct Channel {
  std::uint32_t id = 0;
  std::string topic;
  std::string encoding;         // message encoding, "cdr"
  std::string schema_name;      // e.g. robodds::idl::RobotState
  std::string schema_encoding;  // "omgidl"
  std::string schema;           // the schema text (IDL)
};

enum class StatusLevel { kInfo = 0, kWarning = 1, kError = 2 };

std::string server_info_json(const std::string& name, const std::vector<std::pair<std::string, std::string>>& metadata);
std::string advertise_json(const std::vector<Channel>& channels);
std::string unadvertise_json(const std::vector<std::uint32_t>& channel_ids);
std::string status_json(StatusLevel level, const std::string& message);

/// A client's text message, parsed.
struct ClientOp {
  enum class Kind { kSubscribe, kUnsubscribe, kUnsupported };
  Kind kind = Kind::kUnsupported;
  std::string op;                                                   // the "op" as sent
  std::vector<std::pair<std::uint32_t, std::uint32_t>> subscribe;  // (subscription id, channel id)
  std::vector<std::uint32_t> unsubscribe;                          // subscription ids
};

/// Parses a client's text message. Throws ProtocolError with a one-line reason when it is not
/// JSON, not an object, has no string "op", or a subscribe/unsubscribe whose fields are missing
/// or not unsigned 32-bit integers. Operations other than subscribe/unsubscribe come back as
/// kUnsupported (the caller answers with a status).
ClientOp parse_client_op(const std::string& text);

struct ProtocolError : std::exception {
  explicit ProtocolError(std::string m) : message(std::move(m)) {}
  const char* what() const noexcept override { return message.c_str(); }
  std::string message;
};

/// The binary Message Data frame: opcode 0x01, subscription id (u32 LE), receive time (u64 LE,
/// ns since the epoch), then the payload as is.
std::vector<std::uint8_t> message_data_frame(std::uint32_t subscription_id, std::uint64_t receive_time_ns,
                                             const std::uint8_t* payload, std::size_t size);
/// Bytes before the payload in a Message Data frame.
inline constexpr std::size_t kMessageDataHeaderBytes = 1 + 4 + 8;

}  // namespace robodds::bridge
