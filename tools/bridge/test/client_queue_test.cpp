#include "tools/bridge/client_queue.hpp"

#include <gtest/gtest.h>

namespace robodds::bridge {
namespace {

Queued message(std::uint32_t subscription, std::uint32_t channel) {
  auto sample = std::make_shared<Sample>();
  sample->channel_id = channel;
  return Queued{subscription, sample};
}

TEST(BridgeClientQueue, AFullQueueDropsItsOldestAndCountsThem) {
  ClientQueue queue(3);
  for (std::uint32_t i = 1; i <= 3; ++i) {
    EXPECT_TRUE(queue.push(message(0, i)));
  }
  EXPECT_FALSE(queue.push(message(0, 4)));
  EXPECT_FALSE(queue.push(message(0, 5)));
  EXPECT_EQ(queue.size(), 3u);
  EXPECT_EQ(queue.dropped(), 2u);
  const auto taken = queue.take(2);
  ASSERT_EQ(taken.size(), 2u);
  EXPECT_EQ(taken[0].sample->channel_id, 3u);  // 1 and 2 dropped: the newest are kept
  EXPECT_EQ(taken[1].sample->channel_id, 4u);
  EXPECT_EQ(queue.take(10).size(), 1u);
  EXPECT_EQ(queue.take(10).size(), 0u);
}

TEST(BridgeClientQueue, RemovingASubscriptionLeavesTheOthers) {
  ClientQueue queue(10);
  queue.push(message(1, 5));
  queue.push(message(2, 6));
  queue.push(message(1, 5));
  queue.remove_subscription(1);
  const auto taken = queue.take(10);
  ASSERT_EQ(taken.size(), 1u);
  EXPECT_EQ(taken[0].subscription_id, 2u);
  EXPECT_EQ(queue.dropped(), 0u);  // an unsubscribe is no drop
}

}  // namespace
}  // namespace robodds::bridge
