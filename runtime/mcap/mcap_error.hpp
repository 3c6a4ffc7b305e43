#pragma once
// The one error type of the MCAP library: a file that cannot be written or read as MCAP. A
// ConfigError (bad input to the tools, exit code 2), so callers that catch ConfigError catch it too.
// Every message is one line: "FILE: byte N: reason" (or "FILE: reason" when no offset applies).

#include <cstdint>
#include <string>

#include "runtime/base/error.hpp"

namespace robodds::mcap {

class McapError : public ConfigError {
 public:
  using ConfigError::ConfigError;
};

/// "FILE: byte N: reason".
inline std::string at_byte(const std::string& path, std::uint64_t offset, const std::string& reason) {
  return path + ": byte " + std::to_string(offset) + ": " + reason;
}

}  // namespace robodds::mcap
