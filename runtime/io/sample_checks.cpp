#include "runtime/io/sample_checks.hpp"

#include <cmath>

#include "common/number_text.hpp"

namespace robodds {

namespace field_check {

CheckResult fail(const char* reason, std::string field, std::string detail) {
  return SampleCheckFailure{reason, std::move(field), std::move(detail)};
}

CheckResult within(const char* field, double value, double bound) {
  if (std::fabs(value) <= bound) {
    return std::nullopt;
  }
  return fail(check_reason::kAbsurdMagnitude, field, "is " + shortest_text(value) + ", beyond the bound " + shortest_text(bound));
}

CheckResult variance(const char* field, double value) {
  if (value < 0.0) {
    return fail(check_reason::kNegativeVariance, field, "is " + shortest_text(value) + " (a variance is >= 0)");
  }
  return within(field, value, sample_bounds::kVariance);
}

CheckResult duration(const char* field, double value) {
  if (value < 0.0) {
    return fail(check_reason::kNegativeDuration, field, "is " + shortest_text(value) + " (a duration is >= 0)");
  }
  return within(field, value, sample_bounds::kDurationS);
}

CheckResult first(std::initializer_list<CheckResult> checks) {
  for (const CheckResult& f : checks) {
    if (f) {
      return f;
    }
  }
  return std::nullopt;
}

}  // namespace field_check

using field_check::fail;

CheckResult check_header(const idl::SampleHeader& header, TimeMode mode, std::int64_t wall_now_ns) {
  const std::int64_t stamp = header.stamp_ns();
  if (stamp < 0) {
    return fail(check_reason::kNegativeStamp, "header.stamp_ns", "is " + std::to_string(stamp) + " (negative)");
  }
  // stamp >= 0 here and wall_now_ns is a real clock reading: the difference cannot overflow.
  if (mode == TimeMode::kRealtime && wall_now_ns >= 0 && stamp - wall_now_ns > sample_bounds::kFutureStampToleranceNs) {
    return fail(check_reason::kStampInFuture, "header.stamp_ns",
                "is " + shortest_text(static_cast<double>(stamp - wall_now_ns) * 1e-9) + " s ahead of this host's wall clock (tolerance " +
                    shortest_text(static_cast<double>(sample_bounds::kFutureStampToleranceNs) * 1e-9) + " s)");
  }
  if (header.step() > header.next_step()) {
    return fail(check_reason::kBadHeader, "header.next_step",
                "is " + std::to_string(header.next_step()) + ", before header.step " + std::to_string(header.step()));
  }
  return std::nullopt;
}

CheckResult check_tick(const idl::SimTick& s) { return field_check::duration("step_s", s.step_s()); }

CheckResult check_step_done(const idl::StepDone&) { return std::nullopt; }

CheckResult check_host_alive(const idl::HostAlive&) { return std::nullopt; }  // the header says it all

CheckResult check_host_report(const idl::HostReport& s) {
  if (s.late_steps() > s.ticks()) {  // late steps were run, so they are among the ticks
    return fail(check_reason::kBadSize, "late_steps",
                "is " + std::to_string(s.late_steps()) + ", more than the " + std::to_string(s.ticks()) + " steps run");
  }
  return field_check::duration("worst_lateness_s", s.worst_lateness_s());
}

}  // namespace robodds
