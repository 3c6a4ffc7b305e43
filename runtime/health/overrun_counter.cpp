#include "runtime/health/overrun_counter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace robodds {

std::uint64_t default_max_missed_steps(std::uint64_t total_steps) {
  return static_cast<std::uint64_t>(std::floor(static_cast<double>(total_steps) * kDefaultMaxMissedFraction));
}

std::uint64_t due_steps_between(const std::vector<std::uint64_t>& periods, std::uint64_t from, std::uint64_t to) {
  std::vector<std::uint64_t> used;
  for (std::uint64_t p : periods) {
    if (p == 1) {
      return to > from ? to - from : 0;  // every step is due
    }
    if (p != 0) {
      used.push_back(p);
    }
  }
  std::uint64_t count = 0;
  for (std::uint64_t s = from; s < to; ++s) {
    if (std::any_of(used.begin(), used.end(), [s](std::uint64_t p) { return s % p == 0; })) {
      ++count;
    }
  }
  return count;
}

OverrunCounter::OverrunCounter(double step_s, std::uint64_t max_missed) : step_s_(step_s), max_missed_(max_missed) {}

bool OverrunCounter::ran(std::uint64_t first_due, std::uint64_t step, std::uint64_t missed, double elapsed_s) {
  ++figures_.ticks;
  figures_.missed_steps += missed;
  const double lateness_s = elapsed_s - static_cast<double>(std::min(first_due, step)) * step_s_;
  const bool late = missed > 0 || lateness_s > 0.5 * step_s_;
  if (!late) {
    return false;
  }
  if (lateness_s > 0.5 * step_s_) {
    ++figures_.late_steps;
  }
  figures_.worst_lateness_s = std::max(figures_.worst_lateness_s, lateness_s);
  if (missed == 0) {
    return false;  // late but nothing skipped: counted, not worth a log line each time
  }
  if (!last_warning_s_ || elapsed_s - *last_warning_s_ >= kOverrunWarnIntervalS) {
    last_warning_s_ = elapsed_s;
    return true;
  }
  return false;
}

void OverrunCounter::missed_at_end(std::uint64_t missed) { figures_.missed_steps += missed; }

std::string OverrunCounter::totals_text() const {
  char buf[200];
  std::snprintf(buf, sizeof(buf), "skipped %llu due steps in all (%llu steps run, %llu of them late), worst lateness %.3f s (step %g s)",
                static_cast<unsigned long long>(figures_.missed_steps), static_cast<unsigned long long>(figures_.ticks),
                static_cast<unsigned long long>(figures_.late_steps), figures_.worst_lateness_s, step_s_);
  return buf;
}

}  // namespace robodds
