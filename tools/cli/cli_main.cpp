#include "tools/cli/cli_main.hpp"

#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <unistd.h>

#include "common/did_you_mean.hpp"
#include "runtime/base/error.hpp"
#include "runtime/health/shutdown_watchdog.hpp"

namespace robodds::cli {
namespace {

std::atomic<bool> g_stop{false};
std::atomic<bool> g_second{false};  // a second SIGINT/SIGTERM: a run stopping gracefully aborts
std::atomic<int> g_signals{0};
std::atomic<std::uint64_t> g_stop_at_step{kNoStopStep};
std::atomic<int> g_signal{0};  // the signal that stopped the run: its exit code is 128 + it (130 SIGINT, 143 SIGTERM)

// A signal asks the run loop to stop (outputs are written, exit 128 + signal: 130 for SIGINT, 143
// for SIGTERM, as a shell and `docker stop` expect). Once the run has ended, no
// loop looks at g_stop any more: a signal while the process tears down its DDS entities
// (shutting_down(), a step Fast DDS may block in) ends the process at once with 128 + signal.
void on_signal(int signal_number) {
  g_signal = signal_number;
  if (g_signals.fetch_add(1) >= 1) {
    g_second = true;
  }
  g_stop = true;
  if (shutting_down()) {
    static const char kLine[] = "robodds: error: stopped by a signal during shutdown\n";
    const ssize_t ignored = ::write(STDERR_FILENO, kLine, sizeof(kLine) - 1);
    (void)ignored;
    ::_exit(128 + signal_number);
  }
}

/// SIGUSR1 from the runner (sigqueue): the step to stop after travels in the signal's value, so
/// every child host ends at the same step without a round trip. Lock-free atomics only.
void on_stop_at_step(int /*signal_number*/, siginfo_t* info, void* /*context*/) {
  const std::uint64_t step =
      info != nullptr && info->si_code == SI_QUEUE ? static_cast<std::uint64_t>(reinterpret_cast<std::uintptr_t>(info->si_value.sival_ptr)) : 0;
  std::uint64_t current = g_stop_at_step.load();
  while (step < current && !g_stop_at_step.compare_exchange_weak(current, step)) {
  }
}

/// The message of a command line word that is no subcommand or option of the deepest subcommand
/// parsed, naming the closest: "unknown subcommand 'recrod'; did you mean 'record'? (known: ...)"
/// where that subcommand expects one of its own subcommands, "unknown option '--sed'; did you mean
/// '--seed'?" for an option with a close one. "" otherwise (then CLI11's own message says what is
/// wrong).
std::string unknown_word(CLI::App& app) {
  CLI::App* deepest = &app;
  while (!deepest->get_subcommands().empty()) {
    deepest = deepest->get_subcommands().front();
  }
  const std::vector<std::string> extras = deepest->remaining();
  if (extras.empty() || extras.front().empty()) {
    return "";
  }
  const std::string word = extras.front();
  if (word.front() == '-') {
    // "--sed=3" is the option "--sed"; compared without the dashes, so "--x" is no typo of "--y".
    const std::string option = word.substr(0, word.find('='));
    const std::string bare = option.substr(option.find_first_not_of('-') == std::string::npos ? option.size() : option.find_first_not_of('-'));
    std::vector<std::string> names;
    for (const CLI::Option* known : deepest->get_options()) {
      for (const std::string& name : known->get_lnames()) {
        names.push_back(name);
      }
    }
    const std::vector<std::string> close = closest_names(bare, names);
    if (close.empty()) {
      return "";
    }
    std::vector<std::string> dashed;
    for (const std::string& name : close) {
      dashed.push_back("--" + name);
    }
    return "unknown option '" + option + "'" + did_you_mean(option, dashed);
  }
  const std::vector<CLI::App*> subcommands = deepest->get_subcommands([](CLI::App*) { return true; });
  if (subcommands.empty()) {
    return "";
  }
  std::vector<std::string> names;
  std::string known;
  for (const CLI::App* sub : subcommands) {
    names.push_back(sub->get_name());
    known += (known.empty() ? "" : ", ") + sub->get_name();
  }
  return "unknown subcommand '" + word + "'" + did_you_mean(word, names) + " (known: " + known + ")";
}

}  // namespace

std::string log_level_from_environment() {
  const char* level = std::getenv("ROBODDS_LOG");
  return level != nullptr && *level != '\0' ? level : "info";
}

const std::atomic<bool>& install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  // SA_RESTART: a run that goes on after the first signal (a graceful real-time stop) must not
  // see a system call of another thread fail with EINTR (e.g. a write to a full pipe).
  action.sa_flags = SA_RESTART;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  struct sigaction step_action {};
  step_action.sa_sigaction = on_stop_at_step;
  step_action.sa_flags = SA_SIGINFO | SA_RESTART;
  sigemptyset(&step_action.sa_mask);
  sigaction(SIGUSR1, &step_action, nullptr);
  // A host of a real-time run across processes starts with SIGUSR1 blocked (ProcessGroup::spawn),
  // so that a stop step sent while it was loading waits for this handler.
  sigset_t usr1;
  sigemptyset(&usr1);
  sigaddset(&usr1, SIGUSR1);
  sigprocmask(SIG_UNBLOCK, &usr1, nullptr);
  return g_stop;
}

const StopFlags& stop_flags() {
  static const StopFlags flags{g_stop, g_second, g_stop_at_step};
  return flags;
}

int parse_and_run(CLI::App& app, int argc, char** argv, const std::function<int()>& run) {
  const std::string program = app.get_name().empty() ? "robodds" : app.get_name();
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help and friends: CLI11 prints and exits 0
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Bad command line = bad input: one line and exit code 2, like every other ConfigError.
    const std::string help = app.get_subcommands().empty() ? program + " --help"
                                                           : program + " " + app.get_subcommands().front()->get_name() + " --help";
    const std::string unknown = unknown_word(app);
    std::fprintf(stderr, "%s: error: %s (see %s)\n", program.c_str(), unknown.empty() ? e.what() : unknown.c_str(), help.c_str());
    return 2;
  }
  try {
    return run();
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return 2;
  } catch (const RunConfigError& e) {  // bad set-up found once running (hosts that loaded different files)
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return 2;
  } catch (const RunError& e) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return g_stop ? 128 + g_signal.load() : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return 1;
  }
}

}  // namespace robodds::cli
