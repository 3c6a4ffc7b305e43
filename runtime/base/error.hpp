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

/// "FILE: KEY: reason" (KEY may be empty).
std::string located(const std::string& file, const std::string& key, const std::string& reason);

}  // namespace robodds
