#include "tools/bridge/latency_histogram.hpp"

#include <gtest/gtest.h>

namespace robodds::bridge {
namespace {

TEST(BridgeLatencyHistogram, QuantilesAreBucketUpperEdgesAndTheMaxIsExact) {
  LatencyHistogram h;
  EXPECT_EQ(h.quantile_ns(0.5), 0);
  for (int i = 0; i < 98; ++i) {
    h.add(10'500);  // 10.5 us: bucket [10, 11) us
  }
  h.add(500'000);      // 500 us
  h.add(25'000'000);   // 25 ms: above the range, kept as the maximum
  EXPECT_EQ(h.count(), 100u);
  EXPECT_EQ(h.quantile_ns(0.5), 11'000);
  EXPECT_EQ(h.quantile_ns(0.98), 11'000);
  EXPECT_EQ(h.quantile_ns(0.99), 501'000);
  EXPECT_EQ(h.quantile_ns(1.0), 25'000'000);
  EXPECT_EQ(h.max_ns(), 25'000'000);
  EXPECT_EQ(h.summary(), "100 messages, p50 11 us, p99 501 us, max 25000 us");
}

}  // namespace
}  // namespace robodds::bridge
