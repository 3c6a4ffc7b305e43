#include "runtime/host/health_exchange.hpp"

#include <algorithm>
#include <chrono>
#include <map>

#include "common/number_text.hpp"
#include "runtime/host/host_slot.hpp"
#include "runtime/base/log.hpp"
#include "runtime/topics/topic_catalog.hpp"

namespace robodds {
namespace {

constexpr std::size_t kNameBound = 64;       // string<64> of the IDL
constexpr std::size_t kStageBound = 32;      // StageTiming::stage, string<32>
constexpr std::size_t kTimingBound = 256;    // HostReport::timing, sequence<StageTiming, 256>
constexpr std::size_t kDegradedBound = 512;  // HostReport::degraded, string<512>

std::string bounded(const std::string& text, std::size_t bound = kNameBound) { return text.substr(0, bound); }

std::vector<idl::ReasonCount> to_reasons(const std::map<std::string, std::uint64_t>& counts) {
  std::vector<idl::ReasonCount> out;
  for (const auto& [reason, count] : counts) {
    idl::ReasonCount r;
    r.reason(bounded(reason));
    r.count(count);
    out.push_back(r);
  }
  return out;
}

std::map<std::string, std::uint64_t> from_reasons(const std::vector<idl::ReasonCount>& reasons) {
  std::map<std::string, std::uint64_t> out;
  for (const idl::ReasonCount& r : reasons) {
    out[r.reason().to_string()] += r.count();
  }
  return out;
}

}  // namespace

idl::HostReport to_report(const HostHealth& health, std::uint64_t run_id) {
  idl::HostReport report;
  report.member(bounded(health.member));
  report.run_id(run_id);
  report.ticks(health.figures.ticks);
  report.missed_steps(health.figures.missed_steps);
  report.late_steps(health.figures.late_steps);
  report.worst_lateness_s(health.figures.worst_lateness_s);
  for (const ComponentHealth& component : health.components) {
    for (const InputHealth& input : component.inputs) {
      idl::InputReport r;
      r.component_name(bounded(component.component));
      r.topic(bounded(input.topic));
      r.accepted(input.counts.accepted);
      r.rejected(to_reasons(input.counts.rejected));
      r.adjusted(to_reasons(input.counts.adjusted));
      report.inputs().push_back(r);
    }
  }
  report.undecodable(to_reasons(health.undecodable));
  report.degraded(bounded(health.degraded, kDegradedBound));
  for (const StageTiming& timing : health.timing) {
    if (report.timing().size() == kTimingBound) {
      break;  // the IDL bound: a host with more stages reports its first 256
    }
    idl::StageTiming t;
    t.component_name(bounded(timing.component));
    t.stage(bounded(timing.times.stage, kStageBound));
    t.count(timing.times.count);
    t.median_ms(timing.times.median_ms);
    t.p99_ms(timing.times.p99_ms);
    t.max_ms(timing.times.max_ms);
    report.timing().push_back(t);
  }
  return report;
}

HostHealth from_report(const idl::HostReport& report) {
  HostHealth health;
  health.member = report.member().to_string();
  health.figures.ticks = report.ticks();
  health.figures.missed_steps = report.missed_steps();
  health.figures.late_steps = report.late_steps();
  health.figures.worst_lateness_s = report.worst_lateness_s();
  for (const idl::InputReport& r : report.inputs()) {
    const std::string component = r.component_name().to_string();
    if (health.components.empty() || health.components.back().component != component) {
      health.components.push_back(ComponentHealth{component, {}});
    }
    InputCounts counts;
    counts.accepted = r.accepted();
    counts.rejected = from_reasons(r.rejected());
    counts.adjusted = from_reasons(r.adjusted());
    health.components.back().inputs.push_back(InputHealth{r.topic().to_string(), counts});
  }
  health.undecodable = from_reasons(report.undecodable());
  health.degraded = report.degraded().to_string();
  for (const idl::StageTiming& t : report.timing()) {
    health.timing.push_back(StageTiming{t.component_name().to_string(),
                                        ComputeTimes::Summary{t.stage().to_string(), t.count(), t.median_ms(), t.p99_ms(), t.max_ms()}});
  }
  return health;
}

HealthExchange::HealthExchange(RunContext& run, std::string member, std::uint64_t run_id, std::vector<std::string> others)
    : run_(run), member_(std::move(member)), run_id_(run_id), others_(std::move(others)) {
  state_.mode = run.mode;
  const TopicInfo& topic = topic_info("run/health");
  const std::string profile = qos_profile_for(topic, run.mode, run.single_process);
  output_ = std::make_unique<Output<idl::HostReport>>(run.bus->writer(topic.name, topic.type_name, profile), &state_);
  if (others_.empty()) {
    return;
  }
  detail::InputOptions options;
  options.ignore_step = true;
  options.key_names = topic.key;
  input_ = std::make_unique<Input<idl::HostReport>>(topic.name, member_, &state_, run.notifier, options);
  reader_ = run.bus->reader(
      topic.name, topic.type_name, profile, host_detail::samples_of_run(input_.get(), run_id_),  // this run's reports only
      [this](const std::string& e) { log::warn(member_, "run/health: " + e); });
}

void HealthExchange::exchange(RunFigures& figures, std::uint64_t step, double timeout_s) {
  if (!figures.hosts.empty()) {
    idl::HostReport own = to_report(figures.hosts.front(), run_id_);
    state_.step = step;
    output_->publish_final(own);
  }
  if (!input_) {
    return;
  }
  std::map<std::string, HostHealth> heard;
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(timeout_s));
  while (true) {
    const std::uint64_t seen = run_.notifier->generation();
    for (std::uint64_t key : input_->instances()) {
      for (const idl::HostReport& report : input_->take_new(key)) {
        heard[report.member().to_string()] = from_report(report);
      }
    }
    const bool all = std::all_of(others_.begin(), others_.end(), [&](const std::string& m) { return heard.count(m) != 0; });
    const auto now = std::chrono::steady_clock::now();
    if (all || now >= deadline) {
      break;
    }
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - now);
    run_.notifier->wait(seen, std::min(left, std::chrono::microseconds(50000)));
  }
  std::string missing;
  for (const std::string& member : others_) {
    auto it = heard.find(member);
    if (it != heard.end()) {
      figures.hosts.push_back(std::move(it->second));
    } else {
      figures.hosts_not_heard.push_back(member);
      missing += (missing.empty() ? "" : ", ") + member;
    }
  }
  if (!missing.empty()) {
    log::warn(member_, "no run/health report within " + shortest_text(timeout_s) + " s from host(s) " +
                           missing + "; summary.json lists them as not reported");
  }
}

}  // namespace robodds
