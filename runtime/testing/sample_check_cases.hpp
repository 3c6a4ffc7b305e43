#pragma once
// What the tests of sample checks share (runtime/io/test/sample_checks_test.cpp for the runtime's
// own types, system/test/sample_checks_test.cpp for the robot system's): a plausible sample of
// any message type and the first check it fails, spelled "reason:field".

#include <cstdint>
#include <string>

#include "runtime/io/sample_checks.hpp"

namespace robodds::testing {

inline constexpr std::int64_t kCheckNowNs = 1'800'000'000'000'000'000;  // a wall clock reading, ns

/// "reason:field" of the first check `sample` fails at wall time kCheckNowNs, or "ok".
template <class Msg>
std::string check_reason_of(const Msg& sample, TimeMode mode = TimeMode::kLockstep) {
  const auto failed = check_sample(sample, mode, kCheckNowNs);
  return failed ? failed->reason + ":" + failed->field : "ok";
}

/// A default sample of Msg with a plausible header (step 3, next step 4, stamped kCheckNowNs).
template <class Msg>
Msg plausible_sample() {
  Msg m;
  m.header().step(3);
  m.header().next_step(4);
  m.header().stamp_ns(kCheckNowNs);
  return m;
}

}  // namespace robodds::testing
