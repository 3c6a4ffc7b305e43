#include "runtime/lockstep/history_checkpoints.hpp"

#include <gtest/gtest.h>

namespace robodds {
namespace {

TEST(HistoryCheckpoints, DueStepsSufficeWhileWindowPeriodAndDelayFitTheHistory) {
  // W + p + d - 1 <= depth: no extra wait.
  EXPECT_EQ(history_checkpoint_steps(1, 10, 0, 48), 0u);   // a 10 Hz sensor at 100 Hz
  EXPECT_EQ(history_checkpoint_steps(1, 48, 0, 48), 0u);   // exactly at the bound
  EXPECT_EQ(history_checkpoint_steps(7, 10, 0, 16), 0u);   // 7 + 10 - 1 = 16
  EXPECT_EQ(history_checkpoint_steps(1, 1, 1, 48), 0u);
}

TEST(HistoryCheckpoints, ASlowConsumerWaitsOftenEnoughForTheHistory) {
  // A 1 Hz sensor at 100 Hz (p = 100) with depth 48: wait every 48 steps (1 + 48 + 0 - 1 = 48).
  EXPECT_EQ(history_checkpoint_steps(1, 100, 0, 48), 48u);
  EXPECT_EQ(history_checkpoint_steps(1, 49, 0, 48), 48u);  // one beyond the bound
  // Window 8 and depth 16 for a 10 Hz consumer: 8 + c - 1 <= 16 -> c = 9.
  EXPECT_EQ(history_checkpoint_steps(8, 10, 0, 16), 9u);
  // A delay shortens the gap: 2 + c + 3 - 1 <= 16 -> c = 12.
  EXPECT_EQ(history_checkpoint_steps(2, 100, 3, 16), 12u);
  // Every step: W + d = depth.
  EXPECT_EQ(history_checkpoint_steps(16, 100, 0, 16), 1u);
  EXPECT_EQ(history_checkpoint_steps(10, 100, 6, 16), 1u);
}

TEST(HistoryCheckpoints, NoWaitHelpsWhenWindowAndDelayAloneExceedTheHistory) {
  EXPECT_FALSE(history_checkpoint_steps(17, 1, 0, 16).has_value());
  EXPECT_FALSE(history_checkpoint_steps(10, 100, 7, 16).has_value());
  EXPECT_FALSE(history_checkpoint_steps(1, 1, 0, 0).has_value());
}

}  // namespace
}  // namespace robodds
