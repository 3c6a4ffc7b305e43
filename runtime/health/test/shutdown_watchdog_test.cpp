#include "runtime/health/shutdown_watchdog.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <thread>

namespace robodds {
namespace {

using namespace std::chrono_literals;

TEST(ShutdownWatchdog, AStepThatFinishesInTimeLetsTheProcessGoOn) {
  EXPECT_FALSE(shutting_down());
  {
    ShutdownWatchdog watchdog("deleting nothing", 2000ms);
    EXPECT_TRUE(shutting_down());
  }
  EXPECT_TRUE(shutting_down());  // sticky: the next step may follow, a signal in between ends the process
}

TEST(ShutdownWatchdogDeathTest, AStuckStepEndsTheProcessWithOneLineNamingIt) {
  EXPECT_EXIT(
      {
        ShutdownWatchdog watchdog("deleting the DDS participant 'x'", 100ms);
        std::this_thread::sleep_for(10s);  // stands for a call that never returns
      },
      ::testing::ExitedWithCode(kShutdownTimeoutExit),
      "shutdown: deleting the DDS participant 'x' did not finish within 0.1 s; exiting with code 3");
}

TEST(ShutdownWatchdog, TheLimitComesFromTheEnvironment) {
  ::setenv("ROBODDS_SHUTDOWN_LIMIT_S", "0.25", 1);
  EXPECT_EQ(shutdown_limit(), 250ms);
  ::setenv("ROBODDS_SHUTDOWN_LIMIT_S", "soon", 1);  // one warning, the default
  EXPECT_EQ(shutdown_limit(), std::chrono::milliseconds(static_cast<long long>(kDefaultShutdownLimitS * 1000)));
  ::unsetenv("ROBODDS_SHUTDOWN_LIMIT_S");
  EXPECT_EQ(shutdown_limit(), std::chrono::milliseconds(static_cast<long long>(kDefaultShutdownLimitS * 1000)));
}

}  // namespace
}  // namespace robodds
