#include "sim/evaluator/node/run_summary.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ctime>
#include <vector>

#include "sim/evaluator/node/timing_summary.hpp"

namespace robodds::evaluator {
namespace {

/// Why a run that reached its end is degraded: every host that ran without some of its peers
/// (HostHealth::degraded) and every host whose report never came; empty: none.
std::string degraded_reason(const RunFigures& figures) {
  std::string reason;
  for (const HostHealth& host : figures.hosts) {
    if (!host.degraded.empty()) {
      reason += (reason.empty() ? "" : "; ") + std::string("host '") + host.member + "' " + host.degraded;
    }
  }
  for (const std::string& member : figures.hosts_not_heard) {
    reason += (reason.empty() ? "" : "; ") + std::string("host '") + member + "' did not report (run/health): it may have run alone or not at all";
  }
  return reason;
}

/// Lockstep: "ticks_per_s_by_third": [first, middle, last third of the run's steps] on this
/// host's wall clock from its first tick (start-up left out); a long run whose cost per step
/// grows shows a falling list.
void write_thirds(JsonWriter& json, const RunFigures& run) {
  if (run.thirds_done_at_s.size() != 3 || run.ticks < 3) {
    return;
  }
  const double bounds[4] = {run.thirds_done_at_s[0], run.thirds_done_at_s[1], run.thirds_done_at_s[2], run.wall_time_s};
  const double third_steps[3] = {static_cast<double>(run.ticks / 3), static_cast<double>(run.ticks * 2 / 3 - run.ticks / 3),
                                 static_cast<double>(run.ticks - run.ticks * 2 / 3)};
  std::vector<double> rates;
  for (int i = 0; i < 3; ++i) {
    const double wall_s = bounds[i + 1] - bounds[i];
    rates.push_back(wall_s > 0 ? std::round(third_steps[i] / wall_s * 10.0) / 10.0 : 0.0);
  }
  json.value("ticks_per_s_by_third", rates);
}

/// `wall_ns` (CLOCK_REALTIME) as ISO 8601 UTC to the millisecond: "2026-12-06T16:45:01.234Z".
std::string utc_text(std::int64_t wall_ns) {
  const std::time_t seconds = static_cast<std::time_t>(wall_ns / 1000000000LL);
  std::tm tm{};
  gmtime_r(&seconds, &tm);
  char text[40];
  const std::size_t n = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &tm);
  std::snprintf(text + n, sizeof text - n, ".%03dZ", static_cast<int>((wall_ns / 1000000LL) % 1000));
  return text;
}

}  // namespace

void write_status_section(JsonWriter& json, const RunEnd& end, const RunFigures& figures) {
  if (!end.completed) {
    json.value("status", "failed");
    json.value("reason", end.reason);
    return;
  }
  const std::string degraded = degraded_reason(figures);
  json.value("status", degraded.empty() ? "completed" : "degraded");
  if (!degraded.empty()) {
    json.value("reason", degraded);
  }
  if (!figures.stopped_by.empty()) {  // a real-time run stopped cleanly early: the figures cover the steps that ran
    json.value("stopped_by", figures.stopped_by);
    json.value("stopped_at_s", figures.stopped_at_s);
    json.value("stopped_at_utc", utc_text(figures.stopped_at_wall_ns));
  }
}

void write_run_section(JsonWriter& json, const RunRecording& recording, TimeMode mode) {
  if (recording.deploy_label().empty()) {
    return;
  }
  const RunFigures& run = recording.figures();
  const double ticks_per_s = run.wall_time_s > 0 ? static_cast<double>(run.ticks) / run.wall_time_s : 0.0;
  json.begin_object("run");
  json.value("deploy", recording.deploy_label());
  json.value("mode", mode == TimeMode::kRealtime ? "realtime" : "lockstep");
  if (mode == TimeMode::kLockstep) {
    json.value("lockstep_window", static_cast<std::int64_t>(recording.lockstep_window()));
  }
  json.value("wall_time_s", std::round(run.wall_time_s * 1e6) / 1e6);  // us, like the runner's log
  json.value("ticks", static_cast<std::int64_t>(run.ticks));
  json.value("ticks_per_s", std::round(ticks_per_s * 10.0) / 10.0);
  write_thirds(json, run);
  write_timing_section(json, run);  // the components' compute times (timing_summary.hpp)
  json.end_object();
}

}  // namespace robodds::evaluator
