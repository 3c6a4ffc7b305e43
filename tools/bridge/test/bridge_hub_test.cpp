#include "tools/bridge/bridge_hub.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "runtime/base/error.hpp"

namespace robodds::bridge {
namespace {

using nlohmann::json;

std::shared_ptr<const Sample> sample(std::uint32_t channel, std::uint8_t byte) {
  auto s = std::make_shared<Sample>();
  s->channel_id = channel;
  s->receive_time_ns = 1000;
  s->payload = {0, 1, 0, 0, byte};
  return s;
}

Channel channel(const std::string& topic) { return Channel{0, topic, "cdr", "robodds::idl::RobotState", "omgidl", "idl"}; }

BridgeOptions small_queue(std::size_t n) {
  BridgeOptions o;
  o.client_queue_messages = n;
  return o;
}

TEST(BridgeHub, ANewClientGetsServerInfoAndEveryChannelThenNewOnes) {
  BridgeHub hub(BridgeOptions{}, "robodds bridge", {});
  EXPECT_EQ(hub.add_channel(channel("plant/state")).first, 1u);
  const auto client = hub.connect("c1");
  auto out = hub.take(client, 100);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(json::parse(out[0].text)["op"], "serverInfo");
  EXPECT_EQ(json::parse(out[1].text)["channels"][0]["topic"], "plant/state");
  const auto [id, wake] = hub.add_channel(channel("plant/cmd"));
  EXPECT_EQ(id, 2u);
  EXPECT_EQ(wake, std::vector<BridgeHub::ClientId>{client});
  out = hub.take(client, 100);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(json::parse(out[0].text)["channels"][0]["id"], 2);
}

TEST(BridgeHub, OnlySubscribersGetFramesAndAWakeUpOnlyWhenNonePending) {
  BridgeHub hub(BridgeOptions{}, "b", {});
  const std::uint32_t ch = hub.add_channel(channel("plant/state")).first;
  const auto a = hub.connect("a");
  const auto b = hub.connect("b");
  hub.take(a, 100);
  hub.take(b, 100);
  EXPECT_TRUE(hub.on_text(a, R"({"op":"subscribe","subscriptions":[{"id":7,"channelId":1}]})").empty());
  hub.take(a, 100);
  EXPECT_EQ(hub.publish(sample(ch, 0xAA)), std::vector<BridgeHub::ClientId>{a});
  EXPECT_TRUE(hub.publish(sample(ch, 0xBB)).empty());  // a's wake-up is still pending
  const auto out = hub.take(a, 100);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_TRUE(out[0].binary);
  EXPECT_EQ(out[0].frame[1], 7);  // subscription id 7
  EXPECT_EQ(out[0].frame.back(), 0xAA);
  EXPECT_EQ(out[1].frame.back(), 0xBB);
  EXPECT_TRUE(hub.take(b, 100).empty());
}

TEST(BridgeHub, ASlowClientLosesItsOldestMessagesCountedAndTheOtherNothing) {
  BridgeHub hub(small_queue(4), "b", {});
  const std::uint32_t ch = hub.add_channel(channel("plant/state")).first;
  const auto fast = hub.connect("fast");
  const auto slow = hub.connect("slow");
  for (auto c : {fast, slow}) {
    hub.on_text(c, R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})");
    hub.take(c, 100);
  }
  std::uint64_t fast_got = 0;
  for (int i = 0; i < 100; ++i) {
    hub.publish(sample(ch, static_cast<std::uint8_t>(i)));
    fast_got += hub.take(fast, 100).size();  // the fast client keeps up, the slow one takes nothing
  }
  EXPECT_EQ(fast_got, 100u);
  const auto out = hub.take(slow, 100);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out.back().frame.back(), 99);  // the newest are kept
  for (const ClientStats& s : hub.stats()) {
    EXPECT_EQ(s.dropped, s.name == "slow" ? 96u : 0u) << s.name;
  }
  const ClientStats gone = hub.disconnect(slow);
  EXPECT_EQ(gone.sent, 4u);
  EXPECT_EQ(gone.dropped, 96u);
  EXPECT_EQ(hub.publish(sample(ch, 1)), std::vector<BridgeHub::ClientId>{fast});  // its subscriptions went with it
}

TEST(BridgeHub, NothingOfASubscriptionIsTakenAfterItsUnsubscribe) {
  BridgeHub hub(BridgeOptions{}, "b", {});
  const std::uint32_t ch = hub.add_channel(channel("plant/state")).first;
  const auto c = hub.connect("c");
  hub.on_text(c, R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})");
  hub.take(c, 100);
  hub.publish(sample(ch, 1));
  hub.publish(sample(ch, 2));
  EXPECT_TRUE(hub.on_text(c, R"({"op":"unsubscribe","subscriptionIds":[1]})").empty());
  hub.publish(sample(ch, 3));
  EXPECT_TRUE(hub.take(c, 100).empty());
}

TEST(BridgeHub, BadInputGetsAnErrorStatusAndALogLineEachThenOnlyCounts) {
  BridgeOptions options;
  options.logged_errors_per_client = 3;
  BridgeHub hub(options, "b", {});
  const auto c = hub.connect("c");
  hub.take(c, 100);
  auto lines = hub.on_text(c, "garbage");
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].rfind("bad message: not JSON (", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find("'garbage'"), std::string::npos);
  lines = hub.on_binary(c, 12);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], "binary message of 12 bytes ignored: robodds bridge takes no client data (no clientPublish capability)");
  lines = hub.on_text(c, R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":42}]})");
  ASSERT_EQ(lines.size(), 2u);  // the third, and the line saying no more are logged
  EXPECT_EQ(lines[0], "subscribe: channel 42 is not advertised (subscription 1 ignored)");
  EXPECT_TRUE(hub.on_text(c, R"({"op":"unsubscribe","subscriptionIds":[5]})").empty());
  const auto out = hub.take(c, 100);
  ASSERT_EQ(out.size(), 4u);
  for (const Outgoing& o : out) {
    const json status = json::parse(o.text);
    EXPECT_EQ(status["op"], "status");
    EXPECT_EQ(status["level"], 2);
  }
  EXPECT_EQ(json::parse(out[3].text)["message"], "unsubscribe: no subscription 5");
  EXPECT_EQ(hub.disconnect(c).errors, 4u);
}

TEST(BridgeHub, AChannelWhoseWritersWentIsUnadvertisedWithItsSubscriptionsAndComesBackUnderANewId) {
  BridgeHub hub(BridgeOptions{}, "b", {});
  const std::uint32_t ch = hub.add_channel(channel("plant/state")).first;
  const auto c = hub.connect("c");
  hub.on_text(c, R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})");
  hub.take(c, 100);
  hub.publish(sample(ch, 1));
  EXPECT_TRUE(hub.remove_channel(ch).empty()) << "its wake-up is pending already (the sample's)";
  const auto out = hub.take(c, 100);
  ASSERT_EQ(out.size(), 1u);  // the unadvertise; the queued sample went with the subscription
  EXPECT_EQ(json::parse(out[0].text), json::parse(R"({"op":"unadvertise","channelIds":[1]})"));
  EXPECT_TRUE(hub.remove_channel(ch).empty()) << "twice";
  EXPECT_EQ(hub.add_channel(channel("plant/state")).first, 2u);
  const auto late = hub.connect("late");
  const auto adv = hub.take(late, 100);
  ASSERT_EQ(adv.size(), 2u);
  EXPECT_EQ(json::parse(adv[1].text)["channels"].size(), 1u);  // only the channel advertised now
  EXPECT_EQ(json::parse(adv[1].text)["channels"][0]["id"], 2);
  // The old id is gone: subscribing to it is refused.
  EXPECT_EQ(hub.on_text(c, R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1}]})").size(), 1u);
}

TEST(BridgeHub, OptionsOutOfRangeAreRefusedNamingTheOption) {
  BridgeOptions o;
  o.client_queue_messages = 0;
  try {
    o.validate();
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "--client-queue: 0 messages is outside [1, 1000000]");
  }
  o = BridgeOptions{};
  o.client_send_buffer_bytes = 10;
  EXPECT_THROW(o.validate(), ConfigError);
  o = BridgeOptions{};
  o.client_socket_buffer_bytes = 100;
  EXPECT_THROW(o.validate(), ConfigError);
  o.client_socket_buffer_bytes = 0;  // the system's default
  EXPECT_NO_THROW(o.validate());
}

}  // namespace
}  // namespace robodds::bridge
