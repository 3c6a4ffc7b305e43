#pragma once
// Paper 3 (issue 11): one relative pose topic of the evaluator, keyed (robot_id, peer_id). Its
// samples become CSV rows with the true pose of the peer in the robot's frame appended, and feed
// the stage's errors (relative_pose_metrics.hpp), once the truth of both robots at the sample's
// step is known. Only steps decide what is matched and in which order: in lockstep the figures
// are the same co-located and across processes.

#include <algorithm>
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/angle.hpp"
#include "common/model/pose2.hpp"
#include "common/number_text.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/io/io.hpp"
#include "runtime/io/sample_format.hpp"
#include "sim/evaluator/consistency.hpp"
#include "sim/evaluator/metrics/relative_pose/relative_pose_metrics.hpp"
#include "sim/evaluator/metrics/relative_pose/truth_by_robot.hpp"
#include "sim/evaluator/noise_levels.hpp"
#include "sim/evaluator/module/recorder.hpp"

namespace robodds::evaluator {

/// The stage (summary.json metrics.stages.<stage>) a relative pose topic carries, nullptr if
/// `topic` is not one of them (docs/topics.md).
inline const char* relative_stage_of(const std::string& topic) {
  static const std::pair<const char*, const char*> kStages[] = {
      {"estimate/relative_pose", "pf"},
      {"estimate/relative_pose_uwb", "uwb"},
      {"estimate/relative_pose_window", "window"},
      {"estimate/relative_pose_pf_baseline", "pf_baseline"},
      {"estimate/relative_pose_odometry", "odometry"},
      {"estimate/relative_pose_tc", "tc"},
  };
  for (const auto& [name, stage] : kStages) {
    if (topic == name) {
      return stage;
    }
  }
  return nullptr;
}

/// The instance keys (robot_id, peer_id) of a relative topic: every served robot i with every
/// other robot j of the scenario, in key order.
inline std::vector<std::uint64_t> relative_pair_keys(const std::vector<std::uint64_t>& served,
                                                     const std::vector<std::uint32_t>& all_robots) {
  std::vector<std::uint64_t> keys;
  for (std::uint64_t i : served) {
    for (std::uint32_t j : all_robots) {
      if (j != i) {
        keys.push_back((i << 32) | j);
      }
    }
  }
  return keys;
}

class RelativeRecorder : public TopicRecorder {
 public:
  using Msg = idl::RelativePoseEstimate;
  /// Rows waiting for truth beyond this many are written without it (a robot's plant fell silent).
  static constexpr std::size_t kMaxWaiting = 4096;

  /// Rows are written once `truth` has both robots at the sample's step; the errors go to `metrics`.
  RelativeRecorder(std::string topic, std::string stage, Input<Msg>* input, std::vector<std::uint64_t> keys, double step_s,
                   const TruthByRobot& truth, RelativePoseMetrics& metrics)
      : TopicRecorder(std::move(topic), input), stage_(std::move(stage)), input_(input), keys_(std::move(keys)), step_s_(step_s),
        truth_(truth), metrics_(metrics) {}

  /// Writes its own rows, on the step (settle() needs the step's truth): `writer` unused.
  void open(const std::string& dir, CsvWriter& /*writer*/) override {
    file_.open(dir, topic_, "t_s," + csv_header<Msg>() + ",true_x,true_y,true_theta");
  }
  void collect() override {
    for (std::uint64_t key : keys_) {
      for (Msg& sample : input_->take_new(key)) {
        last_step_ = std::max(last_step_, sample.header().step());
        range_noise_.add(key, sample.range_noise_std_m());
        pending_.push_back(std::move(sample));
        ++rows_;
      }
    }
  }
  /// Writes the waiting samples, in the order taken, whose truth (both robots at the sample's
  /// step) has arrived; a sample without truth at its step gets empty truth columns and is left
  /// out of the errors (an invalid one is still counted as such). Called after every recorder's
  /// collect() of the step (the step's truth is in); `final`: the run is over, nothing waits.
  void settle(bool final) {
    text_.clear();
    const TruthByRobot& truth = truth_;
    while (!pending_.empty()) {
      const Msg& s = pending_.front();
      const std::uint64_t step = s.header().step();
      if (!final && pending_.size() <= kMaxWaiting && !(truth.reached(s.robot_id(), step) && truth.reached(s.peer_id(), step))) {
        break;  // its truth may still come
      }
      const PoseSample* world_i = truth.at(s.robot_id(), step);
      const PoseSample* world_j = truth.at(s.peer_id(), step);
      append_seconds(text_, static_cast<std::int64_t>(s.header().stamp_ns()));
      text_ += ',';
      append_csv_row(text_, s);
      const double t_s = static_cast<double>(step) * step_s_;
      if (world_i != nullptr && world_j != nullptr) {
        const model::Pose2 i{world_i->x, world_i->y, world_i->theta};
        const model::Pose2 j{world_j->x, world_j->y, world_j->theta};
        const model::Pose2 between = model::between(i, j);
        for (double v : {between.x, between.y, between.theta}) {
          text_ += ',';
          append_shortest(text_, v);
        }
        if (s.valid()) {
          metrics_.add_valid(stage_, t_s, i, j, {s.x(), s.y(), s.theta()});
        }
        EstimateError e;
        e.step = step;
        e.valid = s.valid();
        e.ex = s.x() - between.x;
        e.ey = s.y() - between.y;
        e.etheta = wrap_angle(s.theta() - between.theta);
        std::copy(s.cov().begin(), s.cov().end(), e.cov.begin());
        consistency_of(idl::instance_key(s)).add(e);
      } else {
        text_ += ",,,";
      }
      if (!s.valid()) {
        metrics_.add_invalid(stage_, t_s);
      }
      text_ += '\n';
      pending_.pop_front();
    }
    file_.write(text_);
  }
  /// Its estimates against the covariance they report (valid ones, with truth), pooled over pairs.
  ConsistencyStats consistency() const {
    ConsistencyStats all;
    for (const auto& [key, tracker] : consistency_) {
      all = pooled(all, tracker.stats());
    }
    return all;
  }
  /// The range noise each pair's estimator reported at its last sample (issue 27).
  const NoiseLevels& range_noise() const { return range_noise_; }
  const std::string& stage() const { return stage_; }
  /// The oldest step of truth this recorder may still need.
  std::uint64_t truth_needed_from() const {
    return pending_.empty() ? last_step_ : pending_.front().header().step();
  }
 private:
  ConsistencyTracker& consistency_of(std::uint64_t pair) { return consistency_.try_emplace(pair, step_s_).first->second; }

  std::string stage_;
  Input<Msg>* input_;
  std::vector<std::uint64_t> keys_;
  double step_s_;
  const TruthByRobot& truth_;
  RelativePoseMetrics& metrics_;
  std::string text_;
  std::deque<Msg> pending_;     // taken, waiting for the truth of their step
  std::map<std::uint64_t, ConsistencyTracker> consistency_;  // by pair
  std::uint64_t last_step_ = 0; // the newest step taken
  NoiseLevels range_noise_;     // by pair, m
};

}  // namespace robodds::evaluator
