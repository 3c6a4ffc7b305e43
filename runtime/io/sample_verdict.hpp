#pragma once
// Whether a reader takes a sample: the non-finite check, then the type's checks
// (sample_checks.hpp), judged once per delivery in lockstep. Input<Msg> uses it on every
// sample; so does a co-located run's recorder, which observes the bus without an Input
// (ComponentContext::observe_local()).

#include <cstdint>

#include "runtime/bus/bus.hpp"
#include "runtime/io/input_counts.hpp"
#include "runtime/io/sample_checks.hpp"
#include "runtime/io/sample_fields.hpp"

namespace robodds {

/// Why `sample` is refused: a non-finite number first, then the plausibility checks of its
/// message type; nullopt when it passes. Real time compares stamps with the wall clock.
template <class Msg>
CheckResult first_failed_check(const Msg& sample, TimeMode mode) {
  const std::string bad_field = first_non_finite_field(sample);
  if (!bad_field.empty()) {
    return SampleCheckFailure{detail::kRejectNonFinite, bad_field, "is not finite"};
  }
  if (CheckResult failed = check_sample(sample, mode, mode == TimeMode::kRealtime ? wall_clock_now_ns() : 0)) {
    failed->detail += " [" + failed->reason + "]";
    return failed;
  }
  return std::nullopt;
}

/// first_failed_check() of one delivery. In lockstep the checks depend on the sample alone: when
/// another reader of this delivery passed them (SampleMeta::checks_passed), they would pass
/// again, so a co-located run's every reader of a topic checks it once.
template <class Msg>
CheckResult delivery_check(const Msg& sample, const SampleMeta& meta, TimeMode mode) {
  const bool shared = meta.checks_passed != nullptr && mode == TimeMode::kLockstep;
  if (shared && *meta.checks_passed) {
    return std::nullopt;
  }
  CheckResult failed = first_failed_check(sample, mode);
  if (shared && !failed) {
    *meta.checks_passed = true;
  }
  return failed;
}

}  // namespace robodds
