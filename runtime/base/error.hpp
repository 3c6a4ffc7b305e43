#pragma once
// Errors the runtime reports to users. Every message is one line that names what is wrong
// (file, key/element, topic, component, step) and why.

#include <stdexcept>
#include <string>

namespace robodds {

/// Bad user input: parameters, scenario files, QoS profiles, command-line arguments.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A failure while running: a missing input past its timeout, a dead peer, a DDS error.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A run that cannot go on because its set-up is wrong, found only once its hosts meet (hosts of one
/// run that loaded different files, runtime/host/digest_check.hpp). A RunError to the host (it tells
/// the coordinator, its components' on_abort runs, the evaluator writes "failed"); exit code 2, as
/// a ConfigError.
class RunConfigError : public RunError {
 public:
  using RunError::RunError;
};

/// "FILE: KEY: reason" (KEY may be empty).
std::string located(const std::string& file, const std::string& key, const std::string& reason);

}  // namespace robodds
