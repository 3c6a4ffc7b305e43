#include "tools/bridge/client_session.hpp"

#include <gtest/gtest.h>

namespace robodds::bridge {
namespace {

ClientOp subscribe(std::vector<std::pair<std::uint32_t, std::uint32_t>> s) {
  ClientOp op;
  op.kind = ClientOp::Kind::kSubscribe;
  op.op = "subscribe";
  op.subscribe = std::move(s);
  return op;
}

ClientOp unsubscribe(std::vector<std::uint32_t> ids) {
  ClientOp op;
  op.kind = ClientOp::Kind::kUnsubscribe;
  op.op = "unsubscribe";
  op.unsubscribe = std::move(ids);
  return op;
}

TEST(BridgeClientSession, SubscribesAdvertisedChannelsAndRefusesTheRestOneLineEach) {
  ClientSession session;
  std::vector<std::uint32_t> removed;
  const std::set<std::uint32_t> advertised = {1, 2};
  const auto errors = session.apply(subscribe({{10, 1}, {11, 99}, {10, 2}, {12, 1}}), advertised, removed);
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_EQ(errors[0], "subscribe: channel 99 is not advertised (subscription 11 ignored)");
  EXPECT_EQ(errors[1], "subscribe: subscription id 10 is already in use (channel 1)");
  EXPECT_EQ(errors[2], "subscribe: channel 1 is already subscribed as subscription 10");
  ASSERT_NE(session.subscriptions_of(1), nullptr);
  EXPECT_EQ(*session.subscriptions_of(1), std::vector<std::uint32_t>{10});
  EXPECT_EQ(session.subscriptions_of(2), nullptr);
  EXPECT_EQ(session.subscription_count(), 1u);
}

TEST(BridgeClientSession, UnsubscribeForgetsKnownIdsAndNamesUnknownOnes) {
  ClientSession session;
  std::vector<std::uint32_t> removed;
  session.apply(subscribe({{10, 1}}), {1}, removed);
  const auto errors = session.apply(unsubscribe({10, 42}), {1}, removed);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0], "unsubscribe: no subscription 42");
  EXPECT_EQ(removed, std::vector<std::uint32_t>{10});
  EXPECT_EQ(session.subscriptions_of(1), nullptr);
  EXPECT_TRUE(session.apply(subscribe({{10, 1}}), {1}, removed).empty());  // the id may be used again
}

TEST(BridgeClientSession, DroppingAChannelForgetsItsSubscriptions) {
  ClientSession session;
  std::vector<std::uint32_t> removed;
  session.apply(subscribe({{10, 1}, {11, 2}}), {1, 2}, removed);
  EXPECT_EQ(session.drop_channel(1), std::vector<std::uint32_t>{10});
  EXPECT_TRUE(session.drop_channel(1).empty());
  EXPECT_EQ(session.subscriptions_of(1), nullptr);
  EXPECT_EQ(session.subscription_count(), 1u);
  EXPECT_EQ(session.apply(unsubscribe({10}), {2}, removed).size(), 1u);  // 10 is gone
}

TEST(BridgeClientSession, OtherOperationsAreNamedAsUnsupported) {
  ClientSession session;
  std::vector<std::uint32_t> removed;
  ClientOp op;
  op.op = "advertise";
  const auto errors = session.apply(op, {}, removed);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].rfind("operation 'advertise' is not supported by robodds bridge", 0), 0u);
}

}  // namespace
}  // namespace robodds::bridge
