#include "tools/bridge/protocol.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace robodds::bridge {
namespace {

using nlohmann::json;

TEST(BridgeProtocol, ServerInfoAdvertiseAndStatusAreTheSpecsJson) {
  const json info = json::parse(server_info_json("robodds bridge", {{"domain", "7"}}));
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["name"], "robodds bridge");
  EXPECT_TRUE(info["capabilities"].is_array() && info["capabilities"].empty());
  EXPECT_EQ(info["metadata"]["domain"], "7");

  const json adv = json::parse(advertise_json({Channel{3, "plant/state", "cdr", "robodds::idl::RobotState", "omgidl", "module x {};"}}));
  EXPECT_EQ(adv["op"], "advertise");
  ASSERT_EQ(adv["channels"].size(), 1u);
  EXPECT_EQ(adv["channels"][0]["id"], 3);
  EXPECT_EQ(adv["channels"][0]["topic"], "plant/state");
  EXPECT_EQ(adv["channels"][0]["encoding"], "cdr");
  EXPECT_EQ(adv["channels"][0]["schemaName"], "robodds::idl::RobotState");
  EXPECT_EQ(adv["channels"][0]["schemaEncoding"], "omgidl");
  EXPECT_EQ(adv["channels"][0]["schema"], "module x {};");

  EXPECT_EQ(json::parse(unadvertise_json({1, 2}))["channelIds"], json::array({1, 2}));
  const json status = json::parse(status_json(StatusLevel::kError, "bad \xff byte"));  // invalid UTF-8 replaced
  EXPECT_EQ(status["op"], "status");
  EXPECT_EQ(status["level"], 2);
}

TEST(BridgeProtocol, ParsesSubscribeAndUnsubscribe) {
  const ClientOp sub = parse_client_op(R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":4294967295,"channelId":1}]})");
  EXPECT_EQ(sub.kind, ClientOp::Kind::kSubscribe);
  ASSERT_EQ(sub.subscribe.size(), 2u);
  EXPECT_EQ(sub.subscribe[0], std::make_pair(0u, 3u));
  EXPECT_EQ(sub.subscribe[1].first, 4294967295u);
  const ClientOp unsub = parse_client_op(R"({"op":"unsubscribe","subscriptionIds":[0, 7]})");
  EXPECT_EQ(unsub.kind, ClientOp::Kind::kUnsubscribe);
  EXPECT_EQ(unsub.unsubscribe, (std::vector<std::uint32_t>{0, 7}));
  const ClientOp other = parse_client_op(R"({"op":"getParameters","parameterNames":[]})");
  EXPECT_EQ(other.kind, ClientOp::Kind::kUnsupported);
  EXPECT_EQ(other.op, "getParameters");
}

std::string error_of(const std::string& text) {
  try {
    parse_client_op(text);
  } catch (const ProtocolError& e) {
    return e.message;
  }
  return "";
}

TEST(BridgeProtocol, RefusesMalformedMessagesWithOneLineReasons) {
  EXPECT_EQ(error_of("hello garbage").rfind("not JSON (", 0), 0u) << error_of("hello garbage");
  EXPECT_NE(error_of("{\"op\":\"subscribe\"").find("not JSON"), std::string::npos);
  EXPECT_EQ(error_of("[1,2]"), "not a JSON object");
  EXPECT_EQ(error_of("{\"op\":5}"), "no string \"op\"");
  EXPECT_EQ(error_of(R"({"op":"subscribe"})"), "subscribe: \"subscriptions\" must be an array");
  EXPECT_EQ(error_of(R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})"),
            "subscribe: \"id\" is -1, not an unsigned 32-bit integer");
  EXPECT_EQ(error_of(R"({"op":"subscribe","subscriptions":[{"id":1}]})"), "subscribe: missing \"channelId\"");
  EXPECT_EQ(error_of(R"({"op":"subscribe","subscriptions":[{"id":1.5,"channelId":1}]})"),
            "subscribe: \"id\" is 1.5, not an unsigned 32-bit integer");
  EXPECT_EQ(error_of(R"({"op":"unsubscribe","subscriptionIds":["a"]})"),
            "unsubscribe: subscription id \"a\" is not an unsigned 32-bit integer");
  EXPECT_EQ(error_of(R"({"op":"subscribe","subscriptions":[{"id":4294967296,"channelId":1}]})"),
            "subscribe: \"id\" is 4294967296, not an unsigned 32-bit integer");
}

TEST(BridgeProtocol, MessageDataFrameIsOpcodeSubscriptionTimeThenThePayload) {
  const std::uint8_t payload[] = {0x00, 0x01, 0x00, 0x00, 0xAB};
  const auto frame = message_data_frame(0x04030201u, 0x0807060504030201ull, payload, sizeof(payload));
  const std::vector<std::uint8_t> expected = {0x01, 0x01, 0x02, 0x03, 0x04, 0x01, 0x02, 0x03, 0x04, 0x05,
                                              0x06, 0x07, 0x08, 0x00, 0x01, 0x00, 0x00, 0xAB};
  EXPECT_EQ(frame, expected);
}

}  // namespace
}  // namespace robodds::bridge
