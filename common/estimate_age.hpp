#pragma once
// Issue 24 (finding 5): what a controller may do with a pose estimate by its receive age (real
// time). Pure (std only, plain seconds).

#include <cstdint>
#include <string>

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

/// One consumer's view of one producer's estimates (real time): whether the newest one is late,
/// and the reason to log the first time it is. Both controllers hold their last command on a late
/// estimate (issue 24, finding 5).
class LateEstimateWatch {
 public:
  /// `age_s`: receive age of the newest estimate (s); `step`, `next_step`: its header; `step_s`: the
  /// run's step (s); `timeout_s`: the consumer's estimate timeout (s). True when it is late; then,
  /// the first time only, `first_warning` gets e.g. "0.06 s old (> 2 periods of 0.01 s): holding
  /// the last command until it is fresh or stale (not logged again)" (else it is left empty).
  bool late(double age_s, std::uint64_t step, std::uint64_t next_step, double step_s, double timeout_s,
            std::string& first_warning);

 private:
  bool told_ = false;
};

}  // namespace robodds::control
