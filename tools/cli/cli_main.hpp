#pragma once
// What every robodds executable does around its work: SIGINT/SIGTERM set a stop flag (the host
// loops poll it and end cleanly, deleting their participants), command-line mistakes are one
// line and exit 2, and errors map to exit codes: ConfigError 2 (bad input), RunError 1 (a failed
// run; 128 + the signal when one stopped it: 130 SIGINT, 143 SIGTERM), anything else 1. Used by `robodds` and by the component
// executables robodds-<type>.

#include <CLI/CLI.hpp>

#include <atomic>
#include <functional>
#include <string>

namespace robodds::cli {

/// The default log level: $ROBODDS_LOG if set and not empty, else "info".
std::string log_level_from_environment();

/// Installs the SIGINT/SIGTERM handlers once and returns the flag they set.
const std::atomic<bool>& install_stop_handlers();

/// Parses argv into `app` (--help prints and exits 0), then calls `run` and maps its errors to
/// exit codes as above, each error printed as one "<program>: error: ..." line.
int parse_and_run(CLI::App& app, int argc, char** argv, const std::function<int()>& run);

}  // namespace robodds::cli
