#pragma once
// The evaluator's metrics fed sample by sample (node side: it knows the IDL types; the maths is
// in sim/evaluator/track.hpp, waypoint_metrics.hpp, circumnavigation_metrics.hpp and
// relative_pose_metrics.hpp).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/model/diff_drive_kinematics.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/bus/key_index.hpp"
#include "sim/evaluator/circumnavigation_metrics.hpp"
#include "sim/evaluator/handover.hpp"
#include "sim/evaluator/motion_extremes.hpp"
#include "sim/evaluator/relative_pose_metrics.hpp"
#include "sim/evaluator/track.hpp"
#include "sim/evaluator/waypoint_metrics.hpp"

namespace robodds::evaluator {

/// What the metrics need of one robot, updated sample by sample: running figures and the few
/// samples still waiting for their match, never the whole history.
struct RobotMetrics {
  RobotMetrics(std::uint64_t from_step, double gaps_after_s, double step_s, double wheel_base_m)
      : fixes(position_distance, from_step), position(position_distance, from_step),
        heading(heading_difference, from_step), applied(step_s, wheel_base_m), commanded(step_s, wheel_base_m),
        estimate_gaps(gaps_after_s), wheel_base_m(wheel_base_m) {}
  TrackSummary truth;
  TruthWindow recent_truth;
  MatchedError fixes;     // sensor/position against truth
  MatchedError position;  // estimate/pose against truth
  MatchedError heading;
  WaypointTracker waypoints;
  MotionExtremesTracker applied;    // plant/state: what the robot did
  MotionExtremesTracker commanded;  // plant/cmd: what the controller asked for
  std::optional<std::uint64_t> first_valid_step;  // of estimate/pose
  GapTracker estimate_gaps;  // estimate/pose stamps (s): a hot standby's hand-over time
  double wheel_base_m;       // m, the robot's body (shared fact robot_body): its WHEEL_SPEEDS commands
};

/// Which metrics consume truth samples: those whose topics are recorded.
struct TruthConsumers {
  bool fixes = false;
  bool estimates = false;
  bool status = false;
};

/// Paper 3: the true poses of every robot of the scenario (peers included), kept by step while
/// a relative pose estimate of that step may still come (relative_recorder.hpp).
class TruthByRobot {
 public:
  void add(std::uint32_t robot, const PoseSample& sample) { robots_[robot].add(sample); }
  /// Truth of `robot` has arrived up to `step` (a sample at that step is there, or never comes).
  bool reached(std::uint32_t robot, std::uint64_t step) const {
    auto it = robots_.find(robot);
    return it != robots_.end() && it->second.reached(step);
  }
  /// The true pose of `robot` at `step`, nullptr if there is none.
  const PoseSample* at(std::uint32_t robot, std::uint64_t step) const {
    auto it = robots_.find(robot);
    return it != robots_.end() ? it->second.at(step) : nullptr;
  }
  void drop_before(std::uint64_t step) {
    for (auto& [id, window] : robots_) {
      window.drop_before(step);
    }
  }

 private:
  std::map<std::uint32_t, TruthWindow> robots_;
};

/// The metrics of all robots, fed with every recorded sample.
class Metrics {
 public:
  Metrics(std::uint64_t from_step, TruthConsumers consumers) : from_step_(from_step), consumers_(consumers) {}
  // robot() hands out pointers into robots_ (by_number_): not copyable.
  Metrics(const Metrics&) = delete;
  Metrics& operator=(const Metrics&) = delete;

  /// Paper-2 metrics (circumnavigation_metrics.hpp) from plant/state, mission/target and the
  /// recorded observer topics; `b`: the observer's bound on |r''|. Set before the first sample.
  void enable_circumnavigation(double step_s, double b, bool sta, bool linear) {
    circumnavigation_ = std::make_unique<CircumnavigationMetrics>(step_s, b);
    if (sta) {
      circumnavigation_->expect_observer(ObserverKind::kSta);
    }
    if (linear) {
      circumnavigation_->expect_observer(ObserverKind::kLinear);
    }
  }
  const CircumnavigationMetrics* circumnavigation() const { return circumnavigation_.get(); }

  /// Paper-3 metrics (relative_pose_metrics.hpp): plant/state samples are kept by step in
  /// relative_truth() for the relative recorders, which feed relative(). Set before the first sample.
  void enable_relative(double metrics_after_s) { relative_ = std::make_unique<RelativePoseMetrics>(metrics_after_s); }
  RelativePoseMetrics* relative() { return relative_.get(); }
  const RelativePoseMetrics* relative() const { return relative_.get(); }
  TruthByRobot& relative_truth() { return relative_truth_; }

  /// A sample of `topic`: the topic matters only where two topics share a type.
  template <class Msg>
  void observe(const Msg& m, const std::string& /*topic*/) {
    observe(m);
  }
  void observe(const idl::RangeRateEstimate& m, const std::string& topic) {
    if (circumnavigation_ != nullptr) {
      const ObserverKind kind = topic == "observer/range_rate_linear" ? ObserverKind::kLinear : ObserverKind::kSta;
      circumnavigation_->add_estimate(kind, m.robot_id(),
                                      {m.header().step(), m.target_id(), m.range_rate(), m.valid(), m.restarted()});
    }
  }

  template <class Msg>
  void observe(const Msg&) {}
  void observe(const idl::RobotState& m) {
    const PoseSample s{m.header().step(), m.x(), m.y(), m.theta()};
    RobotMetrics& r = robot(m.robot_id());
    r.applied.add({m.header().step(), m.v(), m.omega()});
    r.truth.add(s);
    r.recent_truth.add(s);
    if (relative_ != nullptr) {
      relative_truth_.add(m.robot_id(), s);
    }
    if (circumnavigation_ != nullptr) {
      circumnavigation_->add_truth(m.robot_id(), {m.header().step(), m.x(), m.y(), m.theta(), m.v(), m.omega()});
    }
  }
  void observe(const idl::TargetAssignment& m) {
    if (circumnavigation_ != nullptr) {
      circumnavigation_->add_assignment(m.robot_id(), m.header().step(),
                                        {m.active(), m.target_id(), m.target_x(), m.target_y(), m.desired_radius()});
    }
  }
  void observe(const idl::PositionMeasurement& m) { robot(m.robot_id()).fixes.add({m.header().step(), m.x(), m.y(), 0.0}); }
  void observe(const idl::PoseEstimate& m) {
    const PoseSample s{m.header().step(), m.x(), m.y(), m.theta()};
    robot(m.robot_id()).position.add(s);
    robot(m.robot_id()).heading.add(s);
    robot(m.robot_id()).estimate_gaps.observe(static_cast<double>(m.header().stamp_ns()) * 1e-9);
    if (m.valid() && !robot(m.robot_id()).first_valid_step) {
      robot(m.robot_id()).first_valid_step = m.header().step();
    }
  }
  void observe(const idl::VelocityCommand& m) {
    RobotMetrics& r = robot(m.robot_id());
    const model::Twist twist = m.mode() == idl::WHEEL_SPEEDS
                                   ? model::twist_from_wheel_speeds(m.v_left(), m.v_right(), r.wheel_base_m)
                                   : model::Twist{m.v(), m.omega()};
    r.commanded.add({m.header().step(), twist.v, twist.omega});
  }
  void observe(const idl::ControllerStatus& m) {
    robot(m.robot_id()).waypoints.add_status({m.header().step(), m.waypoints_reached(), m.waypoints_total(), m.done(),
                                              m.switched(), m.switch_distance(), m.epsilon()});
  }
  void observe(const idl::WaypointMission& m) {
    Mission mission;
    for (const idl::Waypoint& w : m.waypoints()) {
      mission.push_back({w.x(), w.y()});
    }
    robot(m.robot_id()).waypoints.set_mission(std::move(mission));
  }

  /// Matches what has arrived with truth and forgets the truth nothing waits for any more.
  void match() {
    for (auto& [id, r] : robots_) {
      r.fixes.match(r.recent_truth);
      r.position.match(r.recent_truth);
      r.heading.match(r.recent_truth);
      r.waypoints.match(r.recent_truth);
      std::uint64_t needed = std::numeric_limits<std::uint64_t>::max();
      if (consumers_.fixes) {
        needed = std::min(needed, r.fixes.needed_from());
      }
      if (consumers_.estimates) {
        needed = std::min({needed, r.position.needed_from(), r.heading.needed_from()});
      }
      if (consumers_.status) {
        needed = std::min(needed, r.waypoints.needed_from());
      }
      r.recent_truth.drop_before(needed);
    }
    if (circumnavigation_ != nullptr) {
      circumnavigation_->update();
    }
  }

  /// The run is over: the paper-2 metrics evaluate what is left.
  void finish() {
    if (circumnavigation_ != nullptr) {
      circumnavigation_->finish();
    }
  }

  /// Gaps between estimate/pose samples count from this stamp (s) on; set before the first sample.
  void set_gaps_after_s(double after_s) { gaps_after_s_ = after_s; }
  /// The simulation step (s) and each robot's wheel base (m; its body), for the wheel speeds and
  /// accelerations of plant/state and plant/cmd; set before the first sample. A robot not named
  /// has `default_wheel_base_m`.
  void set_motion(double step_s, std::map<std::uint32_t, double> wheel_base_m, double default_wheel_base_m) {
    step_s_ = step_s;
    wheel_base_m_ = std::move(wheel_base_m);
    default_wheel_base_m_ = default_wheel_base_m;
  }

  const RobotMetrics* find(std::uint32_t id) const {
    auto it = robots_.find(id);
    return it != robots_.end() ? &it->second : nullptr;
  }

 private:
  /// One O(1) lookup per sample (runtime/bus/key_index.hpp), not a walk down robots_ (log N cache
  /// misses at 1,000 robots); robots_ keeps the id order of match() and the summary.
  RobotMetrics& robot(std::uint32_t id) {
    const auto [number, added] = robot_numbers_.insert(id);
    if (added) {
      const auto base = wheel_base_m_.find(id);
      const double wheel_base_m = base != wheel_base_m_.end() ? base->second : default_wheel_base_m_;
      by_number_.push_back(&robots_.try_emplace(id, from_step_, gaps_after_s_, step_s_, wheel_base_m).first->second);
    }
    return *by_number_[number];
  }

  std::uint64_t from_step_;
  double gaps_after_s_ = 0.0;
  double step_s_ = 0.01;
  std::map<std::uint32_t, double> wheel_base_m_;  // robot -> m
  double default_wheel_base_m_ = 0.5;
  TruthConsumers consumers_;
  std::map<std::uint32_t, RobotMetrics> robots_;
  KeyIndex robot_numbers_;                // robot id -> index in by_number_
  std::vector<RobotMetrics*> by_number_;  // nodes of robots_ (a map's nodes never move)
  std::unique_ptr<CircumnavigationMetrics> circumnavigation_;
  std::unique_ptr<RelativePoseMetrics> relative_;
  TruthByRobot relative_truth_;
};

}  // namespace robodds::evaluator
