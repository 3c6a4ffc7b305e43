// launch.hpp's pure parts: the step every host of a real-time run across processes ends after on
// a graceful stop (Ctrl-C).
#include "runtime/launch/launch.hpp"

#include <gtest/gtest.h>

namespace robodds {
namespace {

TEST(GracefulStopStep, KGracefulStopAheadSAfterNowOnTheRunsSteps) {
  const std::int64_t epoch_ns = 1'000'000'000'000LL;
  // 2.005 s after step 0 with 0.01 s steps: 2.305 s -> step 231 (the first whole step at or after it).
  EXPECT_EQ(graceful_stop_step(epoch_ns, epoch_ns + 2'005'000'000LL, 0.01), 231u);
  EXPECT_EQ(graceful_stop_step(epoch_ns, epoch_ns + 2'000'000'000LL, 0.5), 5u);  // 2.3 s -> 2.5 s
  // Before step 0 (the signal came during start-up): 0.3 s after step 0.
  EXPECT_EQ(graceful_stop_step(epoch_ns, epoch_ns - 1'500'000'000LL, 0.01), 30u);
}

}  // namespace
}  // namespace robodds
