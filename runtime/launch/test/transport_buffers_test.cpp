// The transport buffers of a lockstep host across processes (transport_buffers.hpp).
#include "runtime/launch/transport_buffers.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace robodds {
namespace {

TEST(TransportBuffersTest, TheProfilesOwnServeAStrictRunOfAFewHundredRobots) {
  EXPECT_EQ(transport_buffer_bytes(0, 1), 0U);    // a coordinator, an evaluator: nothing per robot
  EXPECT_EQ(transport_buffer_bytes(3, 1), 0U);
  EXPECT_EQ(transport_buffer_bytes(200, 1), 0U);  // 2 ticks x 200 x 512 B = 200 KiB < 512 KiB
  EXPECT_EQ(transport_buffer_bytes(512, 1), 0U);  // exactly 512 KiB
}

TEST(TransportBuffersTest, GrowsWithTheWindowAndTheRobotsRoundedUpTo64KiB) {
  // 200 robots, window 16: 17 ticks x 200 x 512 B = 1,740,800 B -> 27 x 64 KiB.
  EXPECT_EQ(transport_buffer_bytes(200, 16), 27U * 64 * 1024);
  EXPECT_EQ(transport_buffer_bytes(1000, 1), 16U * 64 * 1024);  // 2 x 1000 x 512 B = 1,024,000 B -> 16 x 64 KiB
  EXPECT_GT(transport_buffer_bytes(200, 32), transport_buffer_bytes(200, 16));
  EXPECT_GT(transport_buffer_bytes(400, 16), transport_buffer_bytes(200, 16));
  EXPECT_EQ(transport_buffer_bytes(200, 0), transport_buffer_bytes(200, 1));  // window 0 is read as 1 (strict)
}

TEST(TransportBuffersTest, NeverMoreThanTheCapEvenForAbsurdFigures) {
  EXPECT_EQ(transport_buffer_bytes(100000, 32), kTransportBufferMaxBytes);
  EXPECT_EQ(transport_buffer_bytes(std::numeric_limits<std::size_t>::max(), 1), kTransportBufferMaxBytes);
  EXPECT_EQ(transport_buffer_bytes(200, std::numeric_limits<std::size_t>::max()), kTransportBufferMaxBytes);
}

}  // namespace
}  // namespace robodds
