#pragma once
// What every robodds executable does around its work: SIGINT/SIGTERM set a stop flag (the host
// loops poll it and end cleanly, deleting their participants), command-line mistakes are one
// line and exit 2, and errors map to exit codes: ConfigError 2 (bad input), RunError 1 (a failed
// run; 128 + the signal when one stopped it: 130 SIGINT, 143 SIGTERM), anything else 1. Used by `robodds` and by the component
// executables robodds-<type>.

#include <CLI/CLI.hpp>

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

namespace robodds::cli {

/// The default log level: $ROBODDS_LOG if set and not empty, else "info".
std::string log_level_from_environment();

/// Installs the SIGINT/SIGTERM (and SIGUSR1) handlers once and returns the flag they set (any
/// SIGINT/SIGTERM).
const std::atomic<bool>& install_stop_handlers();

/// What a run that can stop gracefully (`robodds run --realtime`, its child hosts) reads, set by
/// the handlers install_stop_handlers() installed.
struct StopFlags {
  /// The first SIGINT/SIGTERM: the run stops cleanly at its next step (the same flag as
  /// install_stop_handlers() returns).
  const std::atomic<bool>& first_signal;
  /// A second SIGINT/SIGTERM: the run aborts, as a signal ends any other command.
  const std::atomic<bool>& second_signal;
  /// SIGUSR1 sent with sigqueue() by the runner of `robodds run --realtime --deploy processes` to
  /// its child hosts: stop cleanly after this step (the value it carries), the same step in every
  /// host; kNoStopStep until then. A plain `kill -USR1` (no value) means step 0: at once.
  const std::atomic<std::uint64_t>& stop_at_step;
};
inline constexpr std::uint64_t kNoStopStep = ~std::uint64_t{0};
const StopFlags& stop_flags();

/// Parses argv into `app` (--help prints and exits 0), then calls `run` and maps its errors to
/// exit codes as above, each error printed as one "<program>: error: ..." line.
int parse_and_run(CLI::App& app, int argc, char** argv, const std::function<int()>& run);

}  // namespace robodds::cli
