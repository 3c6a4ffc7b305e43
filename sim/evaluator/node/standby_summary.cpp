#include "sim/evaluator/node/standby_summary.hpp"

#include <cmath>
#include <string>

#include "robodds/idl/robodds.h"

namespace robodds::evaluator {

void StandbySummary::configure(MetricsSetup& setup) {
  active_ = false;
  if (!setup.recorded("estimate/pose")) {
    return;
  }
  for (const ComponentSpec& component : setup.scenario().components) {
    active_ |= !component.standby_for.empty();
  }
  if (active_) {
    setup.on<idl::PoseEstimate>("estimate/pose", [this](const idl::PoseEstimate& m) {
      robots_.get(m.robot_id(), gaps_after_s_).observe(static_cast<double>(m.header().stamp_ns()) * 1e-9);
    });
  }
}

void StandbySummary::write(JsonWriter& json, const std::vector<std::uint64_t>& keys, double start_s) const {
  if (!active_) {
    return;
  }
  const auto round6 = [](double s) { return std::round(s * 1e6) / 1e6; };  // us
  json.begin_object("standby");
  json.value("topic", std::string("estimate/pose"));
  json.begin_object("robots");
  for (std::uint64_t key : keys) {
    const GapTracker* r = robots_.find(static_cast<std::uint32_t>(key));
    const Gap gap = r != nullptr ? r->longest() : Gap{};
    json.begin_object(std::to_string(key));
    json.value("handover_s", round6(gap.length_s));
    json.value("from_s", round6(gap.length_s > 0.0 ? gap.from_s - start_s : 0.0));
    json.value("to_s", round6(gap.length_s > 0.0 ? gap.to_s - start_s : 0.0));
    json.value("samples", static_cast<std::int64_t>(r != nullptr ? r->samples() : 0));
    json.end_object();
  }
  json.end_object();
  json.end_object();
}

}  // namespace robodds::evaluator
