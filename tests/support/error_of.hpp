#pragma once
// Test-only helper: the message of the error of type Error a call throws.

#include <functional>
#include <string>

namespace robodds::test_support {

/// What `f` threw as Error (e.g. ConfigError, RunError), or "" if it threw nothing.
template <class Error>
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace robodds::test_support
