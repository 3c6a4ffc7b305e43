#pragma once
// Test-only helper for the plain parameter structs: the message of their validate().

#include <stdexcept>
#include <string>

namespace robodds::test_support {

/// What params.validate() threw as std::invalid_argument, or "" if it accepted the values.
template <class Params>
std::string validation_error(const Params& params) {
  try {
    params.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace robodds::test_support
