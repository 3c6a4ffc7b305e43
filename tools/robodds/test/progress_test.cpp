// Progress lines: when (terminal: every 0.2 s; piped: every 10 % or 30 s) and what.
#include "tools/robodds/progress.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace robodds {
namespace {

/// The steps at which a pacer prints for a run of `total` steps taking `step_wall_s` each.
std::vector<std::uint64_t> printed(bool terminal, std::uint64_t total, double step_wall_s) {
  ProgressPacer pacer(terminal);
  std::vector<std::uint64_t> out;
  for (std::uint64_t step = 0; step <= total; ++step) {
    if (pacer.due(step, total, static_cast<double>(step) * step_wall_s)) {
      out.push_back(step);
    }
  }
  return out;
}

TEST(Progress, PipedPrintsEveryTenPercentWhenFast) {
  EXPECT_EQ(printed(false, 1000, 0.001), (std::vector<std::uint64_t>{100, 200, 300, 400, 500, 600, 700, 800, 900, 1000}));
}

TEST(Progress, PipedPrintsEveryThirtySecondsWhenSlow) {
  // 1000 steps of 1 s: 10 % would take 100 s, so a line every 30 s (and the end).
  const std::vector<std::uint64_t> slow = printed(false, 1000, 1.0);
  EXPECT_EQ(slow.front(), 30U);
  EXPECT_EQ(slow[1], 60U);
  EXPECT_EQ(slow.back(), 1000U);
  EXPECT_LE(slow.size(), 1000U / 30U + 1U);
}

TEST(Progress, TerminalPrintsAtMostFiveTimesASecondAndAlwaysTheEnd) {
  const std::vector<std::uint64_t> steps = printed(true, 1000, 0.001);  // 1 s
  EXPECT_EQ(steps.size(), 5U);  // 0.2, 0.4, 0.6, 0.8 s and the end
  EXPECT_EQ(steps.back(), 1000U);
  ProgressPacer pacer(true);
  EXPECT_TRUE(pacer.due(5, 5, 0.0));
  EXPECT_FALSE(pacer.due(5, 5, 1.0)) << "the end once";
}

TEST(Progress, TextsSayStepsSimulatedTimeSpeedAndEta) {
  EXPECT_EQ(run_progress_text(12000, 35000, 0.01, 0.6), "step 12000 / 35000 (34 %), 120 of 350 s simulated, 200x real time, ETA 0:01");
  EXPECT_EQ(run_progress_text(0, 100, 0.01, 0.0), "step 0 / 100 (0 %), 0 of 1 s simulated, ETA --:--");
  EXPECT_EQ(replay_progress_text(1200, 5000, 12.0, 50.0, 4.0),
            "message 1200 / 5000 (24 %), 12 of 50 s of the recording, 3x recorded speed, ETA 0:13");
  EXPECT_EQ(clock_text(3723.4), "1:02:03");
  EXPECT_EQ(clock_text(59.6), "1:00");
  EXPECT_EQ(eta_text(1, 4, 10.0), "ETA 0:30");
  EXPECT_EQ(progress_output("x", false, false), "x\n");
  EXPECT_EQ(progress_output("x", true, false), "\rx\033[K");
  EXPECT_EQ(progress_output("x", true, true), "\rx\033[K\n");
}

}  // namespace
}  // namespace robodds
