#include "tools/cli/cli_main.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/base/error.hpp"

namespace robodds::cli {
namespace {

/// parse_and_run on `args` (after the program name) with a --count option, running `run`.
int run_with(const std::vector<std::string>& args, const std::function<int()>& run) {
  CLI::App app{"test", "robodds-test"};
  int count = 0;
  app.add_option("--count", count);
  std::vector<const char*> argv = {"robodds-test"};
  for (const std::string& a : args) {
    argv.push_back(a.c_str());
  }
  return parse_and_run(app, static_cast<int>(argv.size()), const_cast<char**>(argv.data()), run);
}

TEST(CliMain, ExitCodesNameTheKindOfFailure) {
  EXPECT_EQ(run_with({}, [] { return 0; }), 0);
  EXPECT_EQ(run_with({"--count", "3"}, [] { return 7; }), 7);  // the command's own code
  EXPECT_EQ(run_with({}, []() -> int { throw ConfigError("bad input"); }), 2);
  EXPECT_EQ(run_with({}, []() -> int { throw RunError("run failed"); }), 1);
  EXPECT_EQ(run_with({}, []() -> int { throw std::runtime_error("other"); }), 1);
}

// In a child process (the flags are process-wide): the first SIGINT/SIGTERM sets first_signal
// only (a real-time run stops cleanly), the second second_signal (it aborts, exit 128 + signal);
// SIGUSR1 from sigqueue carries the step every host ends after, the smallest one wins, and a
// plain kill -USR1 means step 0 (at once). Exit code 0: every check held, else the failed check's number.
TEST(CliMain, SignalsSetTheFirstAndSecondStopFlagsAndSigusr1CarriesTheStopStep) {
  EXPECT_EXIT(
      {
        install_stop_handlers();
        const StopFlags& flags = stop_flags();
        int failed = 0;
        const auto check = [&failed](int number, bool ok) { failed = failed == 0 && !ok ? number : failed; };
        check(1, !flags.first_signal && !flags.second_signal && flags.stop_at_step == kNoStopStep);
        std::raise(SIGINT);
        check(2, flags.first_signal && !flags.second_signal);
        sigval value{};
        value.sival_ptr = reinterpret_cast<void*>(std::uintptr_t{1234});
        sigqueue(getpid(), SIGUSR1, value);
        check(3, flags.stop_at_step == 1234u && !flags.second_signal);
        value.sival_ptr = reinterpret_cast<void*>(std::uintptr_t{5678});
        sigqueue(getpid(), SIGUSR1, value);
        check(4, flags.stop_at_step == 1234u);
        std::raise(SIGTERM);
        check(5, flags.second_signal);
        std::raise(SIGUSR1);
        check(6, flags.stop_at_step == 0u);
        std::_Exit(failed);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(CliMain, CommandLineMistakesAreBadInputAndDoNotRun) {
  bool ran = false;
  EXPECT_EQ(run_with({"--count", "x"}, [&] { ran = true; return 0; }), 2);
  EXPECT_EQ(run_with({"--nonsense"}, [&] { ran = true; return 0; }), 2);
  EXPECT_FALSE(ran);
  testing::internal::CaptureStdout();
  EXPECT_EQ(run_with({"--help"}, [&] { ran = true; return 0; }), 0);
  EXPECT_NE(testing::internal::GetCapturedStdout().find("--count"), std::string::npos);
  EXPECT_FALSE(ran);
}

TEST(CliMain, AnUnknownSubcommandNamesTheClosestOnes) {
  CLI::App app{"test", "robodds-test"};
  app.require_subcommand(1);
  app.add_subcommand("record", "");
  app.add_subcommand("replay", "");
  CLI::App* security = app.add_subcommand("security", "");
  security->require_subcommand(1);
  security->add_subcommand("init", "");
  const auto error_of = [&app](std::vector<const char*> argv) {
    argv.insert(argv.begin(), "robodds-test");
    testing::internal::CaptureStderr();
    EXPECT_EQ(parse_and_run(app, static_cast<int>(argv.size()), const_cast<char**>(argv.data()), [] { return 0; }), 2);
    return testing::internal::GetCapturedStderr();
  };
  EXPECT_EQ(error_of({"recrod"}),
            "robodds-test: error: unknown subcommand 'recrod'; did you mean 'record'? (known: record, replay, security) "
            "(see robodds-test --help)\n");
  EXPECT_NE(error_of({"security", "inti"}).find("unknown subcommand 'inti'; did you mean 'init'? (known: init)"), std::string::npos);
  EXPECT_EQ(error_of({"zzz"}).find("did you mean"), std::string::npos);
}

TEST(CliMain, AnUnknownOptionNamesTheClosestOne) {
  testing::internal::CaptureStderr();
  EXPECT_EQ(run_with({"--cuont", "3"}, [] { return 0; }), 2);
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "robodds-test: error: unknown option '--cuont'; did you mean '--count'? (see robodds-test --help)\n");
  testing::internal::CaptureStderr();
  EXPECT_EQ(run_with({"--cuont=3"}, [] { return 0; }), 2);
  EXPECT_NE(testing::internal::GetCapturedStderr().find("unknown option '--cuont'; did you mean '--count'?"), std::string::npos);
  testing::internal::CaptureStderr();
  EXPECT_EQ(run_with({"--zzzzz"}, [] { return 0; }), 2);  // nothing close: CLI11's own message
  EXPECT_EQ(testing::internal::GetCapturedStderr().find("did you mean"), std::string::npos);
}

TEST(CliMain, LogLevelComesFromTheEnvironmentOrIsInfo) {
  unsetenv("ROBODDS_LOG");
  EXPECT_EQ(log_level_from_environment(), "info");
  setenv("ROBODDS_LOG", "", 1);
  EXPECT_EQ(log_level_from_environment(), "info");
  setenv("ROBODDS_LOG", "debug", 1);
  EXPECT_EQ(log_level_from_environment(), "debug");
  unsetenv("ROBODDS_LOG");
}

}  // namespace
}  // namespace robodds::cli
