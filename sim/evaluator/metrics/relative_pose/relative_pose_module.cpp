// Paper 3 (issue 11), when relative pose topics (key robot_id, peer_id) are recorded: each one's
// CSV with the true pose of the peer in the robot's frame appended (relative_recorder.hpp), and
// per stage the position and heading errors pooled over its (robot, peer) pairs
// (relative_pose_metrics.hpp). plant/state is then recorded for every robot: the peers' truth.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "robodds/idl/robodds.h"
#include "sim/evaluator/metrics/relative_pose/relative_pose_metrics.hpp"
#include "sim/evaluator/metrics/relative_pose/relative_recorder.hpp"
#include "sim/evaluator/metrics/relative_pose/truth_by_robot.hpp"
#include "sim/evaluator/noise_levels.hpp"
#include "sim/evaluator/module/metrics_module_registry.hpp"

namespace robodds::evaluator {
namespace {

class RelativePoseModule : public MetricsModule {
 public:
  void configure(MetricsSetup& setup) override {
    metrics_.reset();
    recorders_.clear();
    truth_ = TruthByRobot{};
    const std::vector<std::string>& topics = setup.topics();
    if (std::none_of(topics.begin(), topics.end(), [](const std::string& t) { return relative_stage_of(t) != nullptr; })) {
      return;
    }
    metrics_ = std::make_unique<RelativePoseMetrics>(setup.metrics_after_s());
    const std::vector<std::uint32_t> robots = setup.scenario_robots();
    for (const std::string& topic : topics) {
      const char* stage = relative_stage_of(topic);
      if (stage == nullptr) {
        continue;
      }
      if (robots.size() < 2) {
        setup.fail("topics: '" + topic + "' is a relative pose topic (key robot_id, peer_id), but scenario '" +
                   setup.scenario().name + "' has a single robot: there is no peer to estimate");
      }
      if (!setup.recorded("plant/state")) {
        setup.fail("topics: '" + topic + "' needs plant/state in topics too (the true poses its errors "
                   "are measured against)");
      }
      metrics_->expect_stage(stage);
      // Every pair (served robot i, other robot j of the scenario).
      const std::vector<std::uint64_t> pairs = relative_pair_keys(setup.served_robots(), robots);
      setup.record_own(topic, [this, &setup, topic, stage, pairs]() -> std::unique_ptr<RecorderBase> {
        auto* input = &setup.subscribe<idl::RelativePoseEstimate>(topic, Subscription::instances(pairs));
        auto recorder = std::make_unique<RelativeRecorder>(topic, stage, input, pairs, setup.step_s(), truth_, *metrics_);
        recorders_.push_back(recorder.get());
        return recorder;
      });
    }
    setup.record_every_robot("plant/state");
    setup.on<idl::RobotState>("plant/state", [this](const idl::RobotState& m) {
      truth_.add(m.robot_id(), {m.header().step(), m.x(), m.y(), m.theta()});
    });
  }

  void step() override { settle(false); }
  void finish(bool /*completed*/) override { settle(true); }

  /// "stages": {"<stage>": {position_error_m_mean, position_error_m_std, heading_error_deg_mean,
  /// heading_error_deg_std, epochs, invalid_epochs, range_noise_std_m, range_noise_std_max_m, consistency}} for each recorded relative pose
  /// topic; means and stds only with epochs; consistency (sim/evaluator/consistency.hpp) from step
  /// 0, every estimate with truth against the covariance it reports.
  void write_metrics(JsonWriter& json) const override {
    if (metrics_ == nullptr) {
      return;
    }
    json.begin_object("stages");
    for (const auto& [name, stage] : metrics_->stages()) {
      json.begin_object(name);
      if (stage.epochs > 0) {
        json.value("position_error_m_mean", stage.position_error_m_mean);
        json.value("position_error_m_std", stage.position_error_m_std);
        json.value("heading_error_deg_mean", stage.heading_error_deg_mean);
        json.value("heading_error_deg_std", stage.heading_error_deg_std);
      }
      json.value("epochs", static_cast<std::int64_t>(stage.epochs));
      json.value("invalid_epochs", static_cast<std::int64_t>(stage.invalid_epochs));
      ConsistencyStats consistency;
      NoiseLevels range_noise;
      for (const RelativeRecorder* recorder : recorders_) {
        if (recorder->stage() == name) {
          consistency = pooled(consistency, recorder->consistency());
          range_noise.merge(recorder->range_noise());
        }
      }
      // The independent range noise the estimator saw (issue 27): mean over the pairs of their last
      // estimate (m), and the largest; stages that use none (odometry, tc) report none.
      range_noise.write(json, "range_noise_std_m", "range_noise_std_max_m");
      if (consistency.samples > 0) {
        json.begin_object("consistency");
        write_consistency(json, consistency);
        json.end_object();
      }
      json.end_object();
    }
    json.end_object();
  }

  /// Paper 3's mission: the relative pose it is about (estimate/relative_pose, stage "pf") was
  /// valid at some epoch from metrics_after_s on. The other stages are the paper's comparisons:
  /// not judged. nullopt when that topic is not recorded.
  std::optional<std::vector<std::string>> mission_shortfalls() const override {
    if (metrics_ == nullptr) {
      return std::nullopt;
    }
    const auto stages = metrics_->stages();
    const auto pf = stages.find(relative_stage_of("estimate/relative_pose"));
    if (pf == stages.end()) {
      return std::nullopt;
    }
    if (pf->second.epochs > 0) {
      return std::vector<std::string>{};
    }
    return std::vector<std::string>{pf->second.invalid_epochs > 0 ? "relative pose estimate never valid"
                                                                  : "no relative pose estimate"};
  }

 private:
  /// After the step's samples are taken: the recorders write what the truth now allows
  /// (`final`: everything), then the truth no one waits for is dropped.
  void settle(bool final) {
    std::uint64_t needed = std::numeric_limits<std::uint64_t>::max();
    for (RelativeRecorder* recorder : recorders_) {
      recorder->settle(final);
      needed = std::min(needed, recorder->truth_needed_from());
    }
    truth_.drop_before(needed);
  }

  std::unique_ptr<RelativePoseMetrics> metrics_;  // null: no relative pose topic is recorded
  TruthByRobot truth_;
  std::vector<RelativeRecorder*> recorders_;  // owned by the evaluator's core, which keeps them while it runs us
};

std::unique_ptr<MetricsModule> make_relative_pose_module() { return std::make_unique<RelativePoseModule>(); }

/// `robodds run`'s lines: paper 3's Tables 1 and 2, one line per estimator stage (mean +- std).
Headline relative_pose_headline() {
  return {{"stage {*}", "stages.*",
           "position error {position_error_m_mean:2} +- {position_error_m_std:2} m, heading {heading_error_deg_mean:2} +- "
           "{heading_error_deg_std:2} deg"}};
}

}  // namespace
}  // namespace robodds::evaluator

ROBODDS_REGISTER_METRICS_MODULE(relative_pose, "paper 3: relative pose errors per stage, CSVs with the peers' truth", 40,
                                robodds::evaluator::make_relative_pose_module, robodds::evaluator::relative_pose_headline());
