#pragma once
// Plausibility checks of input samples, declared once per message type (not per node): every
// Input runs them on every sample after the non-finite check (io.hpp), so every consumer of
// every topic is covered. A sample that fails is dropped and counted under the check's reason
// (InputCounts::rejected) and logged once per writer and reason.
//
// The runtime checks what it knows: every header, and the content of its own bookkeeping types
// (SimTick, StepDone, HostReport, HostAlive). The content checks of the system's message types are the
// system layer's (system/sample_checks.hpp), installed here with set_content_check() before any
// run starts; an Input of a type without one refuses to be made (require_content_check()). The
// table of checks and bounds is in docs/architecture.md, "Input checks".

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>

#include "robodds/idl/robodds.h"
#include "robodds/idl/robodds_visit.hpp"
#include "runtime/base/error.hpp"
#include "runtime/bus/bus.hpp"

namespace robodds {

/// The first check a sample failed: reason (the InputCounts key, e.g. "bad_enum"), the field it
/// concerns ("mode", "header.stamp_ns") and what was wrong ("is 7, CommandMode has 0..1").
struct SampleCheckFailure {
  std::string reason;
  std::string field;
  std::string detail;
};
using CheckResult = std::optional<SampleCheckFailure>;

/// Rejection reasons (InputCounts::rejected keys) besides detail::kRejectNonFinite.
namespace check_reason {
inline constexpr const char* kNegativeStamp = "negative_stamp";    // header.stamp_ns < 0
inline constexpr const char* kStampInFuture = "stamp_in_future";   // real time: ahead of our wall clock
inline constexpr const char* kBadHeader = "bad_header";            // header.step > header.next_step
inline constexpr const char* kBadEnum = "bad_enum";                // enum value outside its declaration
inline constexpr const char* kBadSize = "bad_size";                // sizes or indices inconsistent
inline constexpr const char* kNegativeVariance = "negative_variance";  // a variance or covariance diagonal < 0
inline constexpr const char* kNegativeDuration = "negative_duration";  // dt_s, step_s < 0
inline constexpr const char* kAbsurdMagnitude = "absurd_magnitude";    // beyond a generous physical bound
}  // namespace check_reason

/// Bounds that hold whatever the system: far beyond any real value, tight enough that nothing
/// above them is used (the system's own bounds: system/sample_checks.hpp).
namespace sample_bounds {
inline constexpr double kVariance = 1e12;  // variances and covariance entries (m^2, rad^2, ...)
inline constexpr double kDurationS = 1e6;  // durations: dt_s, step_s, lateness (s)
/// Real time: how far a sample's header.stamp_ns (the sender's wall clock) may be ahead of this
/// process's wall clock before the sample is refused. Hosts of one system are assumed
/// synchronised (NTP/PTP) far better than this.
inline constexpr std::int64_t kFutureStampToleranceNs = 1'000'000'000;
}  // namespace sample_bounds

/// Building blocks of content checks: each returns the failure of one field, or nullopt.
namespace field_check {
/// A failure of `field` for `reason`, saying `detail` ("is 7, ...").
CheckResult fail(const char* reason, std::string field, std::string detail);
/// |value| <= bound, else absurd_magnitude.
CheckResult within(const char* field, double value, double bound);
/// 0 <= value <= sample_bounds::kVariance (negative_variance, absurd_magnitude).
CheckResult variance(const char* field, double value);
/// 0 <= value <= sample_bounds::kDurationS (negative_duration, absurd_magnitude).
CheckResult duration(const char* field, double value);
/// The first failure of a list of checks, in order.
CheckResult first(std::initializer_list<CheckResult> checks);
}  // namespace field_check

/// Header checks of every type: stamp (negative always; in real time also ahead of `wall_now_ns`
/// by more than the tolerance; in lockstep stamps are sim time and only negative is absurd) and
/// step <= next_step. Overflow-free for any stamp (INT64_MIN, INT64_MAX).
CheckResult check_header(const idl::SampleHeader& header, TimeMode mode, std::int64_t wall_now_ns);

/// The content checks of the runtime's bookkeeping types (header excluded).
CheckResult check_tick(const idl::SimTick& s);
CheckResult check_step_done(const idl::StepDone& s);
CheckResult check_host_report(const idl::HostReport& s);
CheckResult check_host_alive(const idl::HostAlive& s);

/// The content check of message type Msg (header excluded; non-finite numbers are caught before).
template <class Msg>
using ContentCheck = CheckResult (*)(const Msg&);

namespace detail {
template <class Msg>
constexpr ContentCheck<Msg> builtin_content_check() {
  return nullptr;
}
template <>
constexpr ContentCheck<idl::SimTick> builtin_content_check<idl::SimTick>() {
  return &check_tick;
}
template <>
constexpr ContentCheck<idl::StepDone> builtin_content_check<idl::StepDone>() {
  return &check_step_done;
}
template <>
constexpr ContentCheck<idl::HostReport> builtin_content_check<idl::HostReport>() {
  return &check_host_report;
}
template <>
constexpr ContentCheck<idl::HostAlive> builtin_content_check<idl::HostAlive>() {
  return &check_host_alive;
}
/// One per message type in the program: the runtime's own for its bookkeeping types, else what
/// the system layer installed (set_content_check()).
template <class Msg>
struct ContentCheckSlot {
  static inline ContentCheck<Msg> check = builtin_content_check<Msg>();
};
}  // namespace detail

/// Installs the content check of message type Msg (the system layer, before any run starts).
template <class Msg>
void set_content_check(ContentCheck<Msg> check) {
  detail::ContentCheckSlot<Msg>::check = check;
}

/// The content check of Msg; throws ConfigError naming `topic` and the type when none is
/// installed: a topic whose samples nobody checks would let absurd values through unseen.
template <class Msg>
ContentCheck<Msg> require_content_check(const std::string& topic) {
  const ContentCheck<Msg> check = detail::ContentCheckSlot<Msg>::check;
  if (check == nullptr) {
    throw ConfigError("topic " + topic + ": message type " + idl::type_name<Msg>() +
                      " has no sample checks (the system layer installs one per type with set_content_check())");
  }
  return check;
}

/// Every check of `sample` (header, then content); the first failure or nullopt. `wall_now_ns`
/// is read only in real time. Throws ConfigError as require_content_check() without a content check.
template <class Msg>
CheckResult check_sample(const Msg& sample, TimeMode mode, std::int64_t wall_now_ns) {
  if (auto failed = check_header(sample.header(), mode, wall_now_ns)) {
    return failed;
  }
  const ContentCheck<Msg> check = detail::ContentCheckSlot<Msg>::check;
  return check != nullptr ? check(sample) : require_content_check<Msg>(idl::type_name<Msg>())(sample);
}

}  // namespace robodds
