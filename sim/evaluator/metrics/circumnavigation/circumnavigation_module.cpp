// Paper 2 (issue 10), when plant/state and mission/target are recorded: per phase of the mission
// the settling time, radius and spacing errors; per recorded observer topic its range-rate
// errors; and how close |r''| came to the observer's bound b (circumnavigation_metrics.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/number_text.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/log.hpp"
#include "sim/evaluator/metrics/circumnavigation/circumnavigation_metrics.hpp"
#include "sim/evaluator/noise_levels.hpp"
#include "sim/evaluator/module/metrics_module_registry.hpp"
#include "system/robot_facts.hpp"

namespace robodds::evaluator {
namespace {

class CircumnavigationModule : public MetricsModule {
 public:
  /// b is the scenario's shared fact range_accel_bound_mps2 (the bound on |r''| the mission is
  /// designed for), else its default.
  void configure(MetricsSetup& setup) override {
    metrics_.reset();
    noise_std_m_ = {};
    if (!setup.recorded("plant/state") || !setup.recorded("mission/target")) {
      return;
    }
    const system::RangeAccelBound bound = system::range_accel_bound(setup.scenario());
    b_is_default_ = !bound.declared;
    component_name_ = setup.component_name();
    metrics_ = std::make_unique<CircumnavigationMetrics>(setup.step_s(), bound.mps2);
    if (setup.recorded("observer/range_rate")) {
      metrics_->expect_observer(ObserverKind::kSta);
    }
    if (setup.recorded("observer/range_rate_linear")) {
      metrics_->expect_observer(ObserverKind::kLinear);
    }
    if (setup.recorded("observer/range_rate_kf")) {
      metrics_->expect_observer(ObserverKind::kKalman);
    }
    CircumnavigationMetrics& m = *metrics_;
    setup.on<idl::RobotState>("plant/state", [&m](const idl::RobotState& s) {
      m.add_truth(s.robot_id(), {s.header().step(), s.x(), s.y(), s.theta(), s.v(), s.omega()});
    });
    setup.on<idl::TargetAssignment>("mission/target", [&m](const idl::TargetAssignment& a) {
      m.add_assignment(a.robot_id(), a.header().step(), {a.active(), a.target_id(), a.target_x(), a.target_y(), a.desired_radius()});
    });
    for (const auto& [topic, kind] : {std::pair{"observer/range_rate", ObserverKind::kSta},
                                      std::pair{"observer/range_rate_linear", ObserverKind::kLinear},
                                      std::pair{"observer/range_rate_kf", ObserverKind::kKalman}}) {
      setup.on<idl::RangeRateEstimate>(topic, [this, &m, kind = kind](const idl::RangeRateEstimate& e) {
        m.add_estimate(kind, e.robot_id(),
                       {e.header().step(), e.target_id(), e.range_rate(), e.valid(), e.restarted(), e.range_rate_std_mps()});
        noise_std_m_[static_cast<std::size_t>(kind)].add(e.robot_id(), e.range_noise_std_m());
      });
    }
  }

  void step() override {
    if (metrics_ != nullptr) {
      metrics_->update();
    }
  }

  void finish(bool completed) override {
    if (metrics_ == nullptr) {
      return;
    }
    metrics_->finish();
    if (completed && b_is_default_) {  // at the end, once a run (configure may run twice)
      log::info(component_name_, "range_accel_over_b_fraction: the scenario declares no facts.range_accel_bound_mps2, b = " +
                                     shortest_text(metrics_->b()) + " (its default)");
    }
  }

  /// "phase1", "phase2", ... {settle_time_s, radius_rmse_m, spacing_rmse_deg; both null and
  /// "not_settled": why, when the phase's tail is not of a settled formation}, "observer":
  /// {"sta": {...}, "linear": {...}} for each recorded observer topic, and
  /// range_accel_over_b_fraction. A figure without data is left out.
  void write_metrics(JsonWriter& json) const override {
    if (metrics_ == nullptr) {
      return;
    }
    const CircumnavigationMetrics& m = *metrics_;
    const auto optional = [&json](const char* key, const std::optional<double>& v) {
      if (v) {
        json.value(key, *v);
      }
    };
    const CircumnavigationSummary s = m.summary();
    for (std::size_t i = 0; i < s.phases.size(); ++i) {
      const PhaseMetrics& phase = s.phases[i];
      json.begin_object("phase" + std::to_string(i + 1));
      json.value("start_s", phase.start_s);
      json.value("settle_time_s", phase.settle_time_s);
      if (phase.not_settled.empty()) {
        optional("radius_rmse_m", phase.radius_rmse_m);
        optional("spacing_rmse_deg", phase.spacing_rmse_deg);
      } else {
        // Issue 27: no tail figure of a formation that had not settled; null and the reason.
        json.value("radius_rmse_m", std::nan(""));
        json.value("spacing_rmse_deg", std::nan(""));
        json.value("not_settled", phase.not_settled);
      }
      json.end_object();
    }
    const bool any_observer = m.expects(ObserverKind::kSta) || m.expects(ObserverKind::kLinear);
    if (any_observer) {
      json.begin_object("observer");
    }
    for (std::size_t k = 0; k < kObserverKinds; ++k) {
      const auto kind = static_cast<ObserverKind>(k);
      if (!m.expects(kind)) {
        continue;
      }
      const ObserverMetrics& o = s.observers[k];
      json.begin_object(observer_kind_name(kind));
      optional("transient_rmse_mps", o.transient_rmse_mps);
      optional("steady_rmse_mps", o.steady_rmse_mps);
      json.value("convergence_s", o.convergence_s);
      // Issue 27, finding 6: samples outside the convergence tolerance while the truth broke the
      // observer's bound b (excused from convergence_s).
      json.value("convergence_excused_samples", static_cast<std::int64_t>(o.convergence_excused));
      optional("max_error_after_restart_mps", o.max_error_after_restart_mps);
      json.value("restarts", static_cast<std::int64_t>(o.restarts));
      json.value("matched_samples", static_cast<std::int64_t>(o.matched));
      // The range noise the observers estimated (issue 27), at their last sample: the mean over
      // the robots (m), and the largest.
      noise_std_m_[k].write(json, "range_noise_std_m", "range_noise_std_max_m");
      json.begin_object("consistency");
      write_scalar_consistency(json, o.consistency, "worst_error_valid_mps");
      json.end_object();
      json.end_object();
    }
    if (any_observer) {
      json.end_object();
    }
    optional("range_accel_over_b_fraction", s.range_accel_over_b_fraction);
    json.value("range_accel_b", m.b());
  }

  /// Paper 2's mission: the formation settled in every phase of the mission.
  std::optional<std::vector<std::string>> mission_shortfalls() const override {
    if (metrics_ == nullptr) {
      return std::nullopt;
    }
    const CircumnavigationSummary s = metrics_->summary();
    if (s.phases.empty()) {
      return std::vector<std::string>{"no robot was assigned a target"};
    }
    std::vector<std::string> out;
    for (std::size_t i = 0; i < s.phases.size(); ++i) {
      if (s.phases[i].evaluated && s.phases[i].settle_time_s < 0.0) {
        out.push_back("phase " + std::to_string(i + 1) + ": formation never settled");
      }
    }
    return out;
  }

 private:
  std::unique_ptr<CircumnavigationMetrics> metrics_;  // null: the mission is not recorded
  std::array<NoiseLevels, kObserverKinds> noise_std_m_;  // by kind: each robot's last estimate, m
  bool b_is_default_ = false;  // the scenario declares no range_accel_bound_mps2, b is its default
  std::string component_name_;
};

std::unique_ptr<MetricsModule> make_circumnavigation_module() { return std::make_unique<CircumnavigationModule>(); }

/// `robodds run`'s lines: paper 2's figures, each phase's settling and errors, each observer's
/// range-rate errors.
Headline circumnavigation_headline() {
  return {{"{*}", "phase*", "settling: {settle_time_s} s, radius RMSE {radius_rmse_m} m, spacing RMSE {spacing_rmse_deg} deg"},
          {"{*}", "phase*", "no tail figures: {not_settled}"},  // only a phase whose tail is not of a settled formation
          {"observer {*}", "observer.*", "range-rate RMSE {transient_rmse_mps} m/s transient, {steady_rmse_mps} m/s steady"}};
}

}  // namespace
}  // namespace robodds::evaluator

ROBODDS_REGISTER_METRICS_MODULE(circumnavigation, "paper 2: phases' settling, radius and spacing errors; observers' range-rate errors", 30,
                                robodds::evaluator::make_circumnavigation_module, robodds::evaluator::circumnavigation_headline());
