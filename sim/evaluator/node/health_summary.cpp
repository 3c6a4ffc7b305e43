#include "sim/evaluator/node/health_summary.hpp"

#include <cmath>

namespace robodds::evaluator {
namespace {

void write_reasons(JsonWriter& json, const std::string& key, const std::map<std::string, std::uint64_t>& counts) {
  json.begin_object(key);
  for (const auto& [reason, count] : counts) {
    json.value(reason, static_cast<std::int64_t>(count));
  }
  json.end_object();
}

}  // namespace

void write_health_sections(JsonWriter& json, const RunFigures& figures) {
  json.begin_object("hosts");
  for (const HostHealth& host : figures.hosts) {
    json.begin_object(host.member);
    json.value("ticks", static_cast<std::int64_t>(host.figures.ticks));
    json.value("missed_steps", static_cast<std::int64_t>(host.figures.missed_steps));
    json.value("late_steps", static_cast<std::int64_t>(host.figures.late_steps));
    json.value("worst_lateness_s", std::round(host.figures.worst_lateness_s * 1e6) / 1e6);
    write_reasons(json, "undecodable", host.undecodable);
    if (!host.degraded.empty()) {
      json.value("degraded", host.degraded);
    }
    json.end_object();
  }
  for (const std::string& member : figures.hosts_not_heard) {
    json.begin_object(member);
    json.value("reported", false);
    json.end_object();
  }
  json.end_object();
  json.begin_object("inputs");
  for (const HostHealth& host : figures.hosts) {
    for (const ComponentHealth& component : host.components) {
      if (component.inputs.empty()) {
        continue;
      }
      json.begin_object(component.component);
      for (const InputHealth& input : component.inputs) {
        json.begin_object(input.topic);
        json.value("accepted", static_cast<std::int64_t>(input.counts.accepted));
        write_reasons(json, "rejected", input.counts.rejected);
        write_reasons(json, "adjusted", input.counts.adjusted);
        json.end_object();
      }
      json.end_object();
    }
  }
  json.end_object();
}

}  // namespace robodds::evaluator
