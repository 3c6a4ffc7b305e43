// Issue 27: the consistency of estimate/pose: each estimate against truth (plant/state) at its
// step, judged by the covariance it reports (sim/evaluator/consistency.hpp), from step 0 (a wrong start
// belief said valid is what this must see, so metrics_after_s does not apply). Per robot in
// metrics.robots.<id>.estimate_pose, pooled over the served robots in metrics.estimate_pose.

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "robodds/idl/robodds.h"
#include "sim/evaluator/consistency.hpp"
#include "sim/evaluator/module/metrics_module_registry.hpp"
#include "sim/evaluator/module/per_robot.hpp"
#include "sim/evaluator/noise_levels.hpp"
#include "sim/evaluator/track.hpp"

namespace robodds::evaluator {
namespace {

/// An estimate waiting for truth at its step.
struct PendingEstimate {
  PoseSample pose;
  bool valid = false;
  std::array<double, 9> cov{};
};

struct RobotConsistency {
  explicit RobotConsistency(double step_s) : tracker(step_s) {}
  TruthWindow truth;
  std::deque<PendingEstimate> pending;  // step order
  std::uint64_t judged_through = 0;    // estimates come in step order: none before this step is still to come
  ConsistencyTracker tracker;
};

class ConsistencyModule : public MetricsModule {
 public:
  void configure(MetricsSetup& setup) override {
    if (!setup.recorded("estimate/pose") || !setup.recorded("plant/state")) {
      return;
    }
    active_ = true;
    served_ = setup.served_robots();
    step_s_ = setup.step_s();
    setup.on<idl::RobotState>("plant/state", [this](const idl::RobotState& m) {
      robot(m.robot_id()).truth.add({m.header().step(), m.x(), m.y(), m.theta()});
    });
    setup.on<idl::PoseEstimate>("estimate/pose", [this](const idl::PoseEstimate& m) {
      PendingEstimate e;
      e.pose = {m.header().step(), m.x(), m.y(), m.theta()};
      e.valid = m.valid();
      std::copy(m.cov().begin(), m.cov().end(), e.cov.begin());
      robot(m.robot_id()).pending.push_back(e);
      fix_noise_.add(m.robot_id(), m.fix_noise_std_m());
    });
  }

  /// Judges the estimates whose step truth has reached; keeps the truth the others still need.
  void step() override {
    for (auto& [id, r] : robots_.all()) {
      while (!r.pending.empty() && r.truth.reached(r.pending.front().pose.step)) {
        const PendingEstimate& e = r.pending.front();
        if (const PoseSample* truth = r.truth.at(e.pose.step)) {
          r.tracker.add({e.pose.step, e.valid, e.pose.x - truth->x, e.pose.y - truth->y, heading_difference(*truth, e.pose), e.cov});
        }
        r.judged_through = e.pose.step;
        r.pending.pop_front();
      }
      r.truth.drop_before(r.pending.empty() ? r.judged_through : r.pending.front().pose.step);
    }
  }

  void write_robot(JsonWriter& json, std::uint32_t id) const override {
    const RobotConsistency* r = robots_.find(id);
    if (r == nullptr || r->tracker.stats().samples == 0) {
      return;
    }
    json.begin_object("estimate_pose");
    write_consistency(json, r->tracker.stats());
    NoiseLevels own;  // the same keys as the pooled figure's, of this robot alone
    own.add(id, fix_noise_.last(id));
    own.write(json, "fix_noise_std_m", "fix_noise_std_max_m");
    json.end_object();
  }

  void write_metrics(JsonWriter& json) const override {
    if (!active_) {
      return;
    }
    ConsistencyStats all;
    for (std::uint64_t key : served_) {
      if (const RobotConsistency* r = robots_.find(static_cast<std::uint32_t>(key))) {
        all = pooled(all, r->tracker.stats());
      }
    }
    if (all.samples == 0) {
      return;
    }
    json.begin_object("estimate_pose");
    write_consistency(json, all);
    // The fix noise the estimator estimated (issue 27), at its last sample: mean over the robots
    // (m, per axis), and the largest.
    fix_noise_.write(json, "fix_noise_std_m", "fix_noise_std_max_m");
    json.end_object();
  }

 private:
  RobotConsistency& robot(std::uint32_t id) { return robots_.get(id, step_s_); }

  bool active_ = false;
  std::vector<std::uint64_t> served_;
  double step_s_ = 0.0;
  PerRobot<RobotConsistency> robots_;
  NoiseLevels fix_noise_;  // each robot's last estimated fix noise, m
};

std::unique_ptr<MetricsModule> make_consistency_module() { return std::make_unique<ConsistencyModule>(); }

/// `robodds run`'s line: is the estimate as good as it says?
Headline consistency_headline() {
  return {{"estimate consistency", "estimate_pose",
           "{overconfident_fraction} of valid samples outside their reported 3 sigma (longest {longest_overconfident_s} s); "
           "worst while valid {worst_position_error_valid_m} m, {worst_heading_error_valid_deg} deg"}};
}

}  // namespace
}  // namespace robodds::evaluator

ROBODDS_REGISTER_METRICS_MODULE(consistency, "issue 27: estimate/pose against its reported covariance: over-confident fraction, worst error while valid", 50,
                                robodds::evaluator::make_consistency_module, robodds::evaluator::consistency_headline());
