// Paper 1 (way-point missions): per robot the true track (path length, final pose), the errors
// of sensor/position and estimate/pose against truth at the same step after metrics_after_s,
// and the way-point figures of control/status and mission/waypoints (waypoint_metrics.hpp);
// pooled over the served robots at the top level.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/angle.hpp"
#include "common/number_text.hpp"
#include "robodds/idl/robodds.h"
#include "sim/evaluator/metrics/waypoints/leg_deviation.hpp"
#include "sim/evaluator/metrics/waypoints/waypoint_metrics.hpp"
#include "sim/evaluator/module/metrics_module_registry.hpp"
#include "sim/evaluator/module/per_robot.hpp"
#include "sim/evaluator/track.hpp"

namespace robodds::evaluator {
namespace {

constexpr double kDegPerRad = 180.0 / kPi;

/// What the figures need of one robot, updated sample by sample: running figures and the few
/// samples still waiting for their match, never the whole history.
struct RobotFigures {
  explicit RobotFigures(std::uint64_t from_step)
      : fixes(position_distance, from_step), position(position_distance, from_step), heading(heading_difference, from_step) {}
  TrackSummary truth;
  TruthWindow recent_truth;
  MatchedError fixes;     // sensor/position against truth
  MatchedError position;  // estimate/pose against truth
  MatchedError heading;
  WaypointTracker waypoints;
  LegDeviation legs;         // the true track against the mission's legs (issue 28)
  bool estimated = false;    // an estimate/pose sample came
  bool ever_valid = false;   // ... and one of them was valid
  /// The step from which the estimate, valid before, has not been valid (issue 27: a robot that
  /// stopped for it says so); none while valid or before the first valid sample.
  std::optional<std::uint64_t> invalid_since_step;
};

class WaypointsModule : public MetricsModule {
 public:
  void configure(MetricsSetup& setup) override {
    served_ = setup.served_robots();
    step_s_ = setup.step_s();
    from_step_ = setup.metrics_from_step();
    // Truth is kept for the matches of the recorded topics only.
    fixes_recorded_ = setup.recorded("sensor/position");
    estimates_recorded_ = setup.recorded("estimate/pose");
    status_recorded_ = setup.recorded("control/status");
    setup.on<idl::RobotState>("plant/state", [this](const idl::RobotState& m) {
      const PoseSample s{m.header().step(), m.x(), m.y(), m.theta()};
      RobotFigures& r = robot(m.robot_id());
      r.truth.add(s);
      r.recent_truth.add(s);
      if (status_recorded_) {  // without the controller's status no truth sample finds its leg
        r.legs.add_truth(s.step, s.x, s.y);
      }
    });
    setup.on<idl::PositionMeasurement>("sensor/position", [this](const idl::PositionMeasurement& m) {
      robot(m.robot_id()).fixes.add({m.header().step(), m.x(), m.y(), 0.0});
    });
    setup.on<idl::PoseEstimate>("estimate/pose", [this](const idl::PoseEstimate& m) {
      const PoseSample s{m.header().step(), m.x(), m.y(), m.theta()};
      RobotFigures& r = robot(m.robot_id());
      r.position.add(s);
      r.heading.add(s);
      r.estimated = true;
      r.ever_valid = r.ever_valid || m.valid();
      if (m.valid()) {
        r.invalid_since_step.reset();
      } else if (r.ever_valid && !r.invalid_since_step) {
        r.invalid_since_step = m.header().step();
      }
    });
    setup.on<idl::ControllerStatus>("control/status", [this](const idl::ControllerStatus& m) {
      RobotFigures& r = robot(m.robot_id());
      r.waypoints.add_status({m.header().step(), m.waypoints_reached(), m.waypoints_total(), m.done(), m.switched(),
                              m.switch_distance(), m.epsilon()});
      r.legs.add_status(m.header().step(), m.waypoint_index(), m.done());
    });
    setup.on<idl::WaypointMission>("mission/waypoints", [this](const idl::WaypointMission& m) {
      Mission mission;
      for (const idl::Waypoint& w : m.waypoints()) {
        mission.push_back({w.x(), w.y()});
      }
      RobotFigures& r = robot(m.robot_id());
      r.legs.set_mission(mission);
      r.waypoints.set_mission(std::move(mission));
    });
  }

  /// Matches what has arrived with truth and forgets the truth nothing waits for any more.
  void step() override {
    for (auto& [id, r] : robots_.all()) {
      r.fixes.match(r.recent_truth);
      r.position.match(r.recent_truth);
      r.heading.match(r.recent_truth);
      r.waypoints.match(r.recent_truth);
      std::uint64_t needed = std::numeric_limits<std::uint64_t>::max();
      if (fixes_recorded_) {
        needed = std::min(needed, r.fixes.needed_from());
      }
      if (estimates_recorded_) {
        needed = std::min({needed, r.position.needed_from(), r.heading.needed_from()});
      }
      if (status_recorded_) {
        needed = std::min(needed, r.waypoints.needed_from());
      }
      r.recent_truth.drop_before(needed);
    }
  }

  void write_robot(JsonWriter& json, std::uint32_t id) const override {
    const RobotFigures* r = robots_.find(id);
    if (r == nullptr || r->truth.empty()) {
      return;
    }
    const PoseSample& last = r->truth.last();
    json.value("path_length_m", r->truth.path_length());
    json.value("final_x_m", last.x).value("final_y_m", last.y).value("final_theta_rad", last.theta);
    json.value("state_samples", static_cast<std::int64_t>(r->truth.count()));
    if (r->fixes.seen()) {
      const ErrorStats e = r->fixes.stats();
      json.value("measurement_rmse_m", e.rmse).value("measurement_samples", static_cast<std::int64_t>(e.count));
    }
    if (r->position.seen()) {
      json.value("pf_rmse_m", r->position.stats().rmse).value("heading_rmse_deg", r->heading.stats().rmse * kDegPerRad);
    }
    write_waypoint_metrics(json, *r);
  }

  void write_single_robot(JsonWriter& json, std::uint32_t id) const override {
    const RobotFigures* r = robots_.find(id);
    if (r != nullptr && r->waypoints.has_status()) {
      write_waypoint_metrics(json, *r);
    }
  }

  /// The errors pooled over the served robots with truth.
  void write_metrics(JsonWriter& json) const override {
    PooledRmse fix_rmse;
    PooledRmse estimate_rmse;
    PooledRmse heading_rmse_rad;
    for (std::uint64_t key : served_) {
      const RobotFigures* r = robots_.find(static_cast<std::uint32_t>(key));
      if (r == nullptr || r->truth.empty()) {
        continue;
      }
      if (r->fixes.seen()) {
        fix_rmse.add(r->fixes.stats());
      }
      if (r->position.seen()) {
        estimate_rmse.add(r->position.stats());
        heading_rmse_rad.add(r->heading.stats());
      }
    }
    if (!fix_rmse.empty()) {
      json.value("measurement_rmse_m", fix_rmse.rmse());
    }
    if (!estimate_rmse.empty()) {
      json.value("pf_rmse_m", estimate_rmse.rmse());
    }
    if (!heading_rmse_rad.empty()) {
      json.value("heading_rmse_deg", heading_rmse_rad.rmse() * kDegPerRad);
    }
  }

  /// Paper 1's mission: every served robot reached all its way-points ("robot N: " before each
  /// reason when it serves several); a robot whose estimate was never valid says so too.
  std::optional<std::vector<std::string>> mission_shortfalls() const override {
    if (!status_recorded_) {
      return std::nullopt;
    }
    std::vector<std::string> out;
    bool judged = false;
    for (std::uint64_t key : served_) {
      const RobotFigures* r = robots_.find(static_cast<std::uint32_t>(key));
      if (r == nullptr || !r->waypoints.has_status() || !r->waypoints.has_mission()) {
        continue;
      }
      judged = true;
      const std::string who = served_.size() > 1 ? "robot " + std::to_string(key) + ": " : "";
      const WaypointMetrics m = r->waypoints.metrics(r->truth.empty() ? nullptr : &r->truth.last(), step_s_);
      if (m.waypoints_reached < m.waypoints_total) {
        out.push_back(who + std::to_string(m.waypoints_reached) + " of " + std::to_string(m.waypoints_total) +
                      " way-points reached");
        if (r->invalid_since_step) {
          const double since_s = std::round(static_cast<double>(*r->invalid_since_step) * step_s_ * 1000.0) / 1000.0;  // ms
          out.push_back(who + "estimate not valid from " + shortest_text(since_s) + " s to the end");
        }
      }
      if (r->estimated && !r->ever_valid) {
        out.push_back(who + "estimate never valid");
      }
    }
    if (!judged) {
      return std::nullopt;
    }
    return out;
  }

 private:
  RobotFigures& robot(std::uint32_t id) { return robots_.get(id, from_step_); }

  void write_waypoint_metrics(JsonWriter& json, const RobotFigures& r) const {
    if (!r.waypoints.has_status() || !r.waypoints.has_mission()) {
      return;
    }
    const WaypointMetrics m = r.waypoints.metrics(r.truth.empty() ? nullptr : &r.truth.last(), step_s_);
    json.value("waypoints_reached", static_cast<std::int64_t>(m.waypoints_reached));
    json.value("waypoints_total", static_cast<std::int64_t>(m.waypoints_total));
    json.value("time_to_final_s", m.time_to_final_s);
    json.value("switch_distance_estimate_m", m.switch_distance_estimate_m);
    json.value("switch_distance_true_m", m.switch_distance_true_m);
    json.value("final_error_true_m", m.final_error_true_m);
    json.value("epsilon", m.epsilon_m);
    if (const auto legs = r.legs.figures()) {
      json.value("cross_track_rms_m", legs->cross_track_rms_m).value("cross_track_max_m", legs->cross_track_max_m);
    }
  }

  std::vector<std::uint64_t> served_;
  double step_s_ = 0.0;
  std::uint64_t from_step_ = 0;
  bool fixes_recorded_ = false;
  bool estimates_recorded_ = false;
  bool status_recorded_ = false;
  PerRobot<RobotFigures> robots_;
};

std::unique_ptr<MetricsModule> make_waypoints_module() { return std::make_unique<WaypointsModule>(); }

/// `robodds run`'s lines: paper 1's Table 1 figures (way-points, final error) and the estimate's
/// errors; with one robot its keys are at the top level, with several only the pooled RMSEs are.
Headline waypoints_headline() {
  return {{"way-points", "", "{waypoints_reached} of {waypoints_total} reached, time to the last: {time_to_final_s} s"},
          {"final error", "", "{final_error_true_m} m from the last way-point (true pose)"},
          {"estimate RMSE", "", "{pf_rmse_m} m position, {heading_rmse_deg} deg heading"},
          {"fix RMSE", "", "{measurement_rmse_m} m (sensor/position)"}};
}

}  // namespace
}  // namespace robodds::evaluator

ROBODDS_REGISTER_METRICS_MODULE(waypoints, "paper 1: the true track, measurement/pf/heading RMSE, way-point figures", 10,
                                robodds::evaluator::make_waypoints_module, robodds::evaluator::waypoints_headline());
