#pragma once
// Issue 24 (finding 5): what a controller may do with a pose estimate by its receive age (real
// time). Pure (std only, plain seconds).

#include <cstdint>

namespace robodds::control {

enum class EstimateAge {
  kFresh,  // at most two of its producer's periods old: track on it
  kLate,   // older, up to the timeout: a frozen pose is no news; hold the last command, never raise it
  kStale,  // older than the timeout: zero command
};

/// `age_s`: since this process received the estimate (s); `producer_period_s`: the time between
/// two estimates of its producer (s; <= 0 or not finite when unknown, e.g. its last sample:
/// then anything older than 0 is late); `timeout_s`: the controller's estimate_timeout_s.
/// Two periods, not one: a sample a little late on a busy machine must not count.
EstimateAge classify_estimate_age(double age_s, double producer_period_s, double timeout_s);

/// The producer's period (s) from a sample's header, as it announced it: (next_step - step) steps
/// of `step_s` (s). 0 (unknown) when it announces no next sample: next_step not after step, or
/// UINT64_MAX (the runtime's kNeverAgain: its last sample).
double producer_period_s(std::uint64_t step, std::uint64_t next_step, double step_s);

}  // namespace robodds::control
