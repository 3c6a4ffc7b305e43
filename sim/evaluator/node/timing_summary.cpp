#include "sim/evaluator/node/timing_summary.hpp"

#include <algorithm>
#include <cmath>

namespace robodds::evaluator {

std::vector<StageFigures> stage_figures(const std::vector<HostHealth>& hosts) {
  std::vector<StageFigures> out;
  for (const HostHealth& host : hosts) {
    for (const StageTiming& timing : host.timing) {
      const ComputeTimes::Summary& t = timing.times;
      auto it = std::find_if(out.begin(), out.end(), [&](const StageFigures& s) { return s.stage == t.stage; });
      if (it == out.end()) {
        out.push_back(StageFigures{t.stage, t.median_ms, t.p99_ms, t.max_ms, t.count, timing.component, 1});
        continue;
      }
      it->median_ms = std::max(it->median_ms, t.median_ms);
      if (t.p99_ms > it->p99_ms) {
        it->p99_ms = t.p99_ms;
        it->component = timing.component;
      }
      it->max_ms = std::max(it->max_ms, t.max_ms);
      it->cycles += t.count;
      ++it->components;
    }
  }
  return out;
}

void write_timing_section(JsonWriter& json, const RunFigures& figures) {
  const auto us = [](double ms) { return std::round(ms * 1e3) / 1e3; };
  json.begin_object("timing");
  for (const StageFigures& s : stage_figures(figures.hosts)) {
    json.begin_object(s.stage);
    json.value("cycle_ms_median", us(s.median_ms));
    json.value("cycle_ms_p99", us(s.p99_ms));
    json.value("cycle_ms_max", us(s.max_ms));
    json.value("cycles", static_cast<std::int64_t>(s.cycles));
    json.value("component", s.component);
    json.value("components", static_cast<std::int64_t>(s.components));
    json.end_object();
  }
  json.end_object();
}

}  // namespace robodds::evaluator
