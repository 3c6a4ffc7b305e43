// Issue 12: per robot the extremes of what the plant applied (plant/state) and, apart, of what
// the controller commanded (plant/cmd), over the whole run (motion_extremes.hpp); and when
// estimate/pose first said valid. Each only when its topic is recorded.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "common/model/diff_drive_kinematics.hpp"
#include "common/model/robot_body.hpp"
#include "robodds/idl/robodds.h"
#include "sim/evaluator/metrics/motion/motion_extremes.hpp"
#include "sim/evaluator/module/metrics_module_registry.hpp"
#include "sim/evaluator/module/per_robot.hpp"
#include "system/robot_facts.hpp"

namespace robodds::evaluator {
namespace {

struct RobotFigures {
  RobotFigures(double step_s, double wheel_base_m)
      : applied(step_s, wheel_base_m), commanded(step_s, wheel_base_m), wheel_base_m(wheel_base_m) {}
  MotionExtremesTracker applied;    // plant/state: what the robot did
  MotionExtremesTracker commanded;  // plant/cmd: what the controller asked for
  bool estimates_seen = false;      // of estimate/pose
  std::optional<std::uint64_t> first_valid_step;  // of estimate/pose
  double wheel_base_m;  // m, the robot's body (shared fact robot_body): its WHEEL_SPEEDS commands
};

class MotionModule : public MetricsModule {
 public:
  void configure(MetricsSetup& setup) override {
    step_s_ = setup.step_s();
    for (std::uint32_t id : setup.scenario_robots()) {
      wheel_base_m_[id] = system::robot_body(setup.scenario(), id).wheel_base_m;
    }
    setup.on<idl::RobotState>("plant/state", [this](const idl::RobotState& m) {
      robot(m.robot_id()).applied.add({m.header().step(), m.v(), m.omega()});
    });
    setup.on<idl::VelocityCommand>("plant/cmd", [this](const idl::VelocityCommand& m) {
      RobotFigures& r = robot(m.robot_id());
      const model::Twist twist = m.mode() == idl::WHEEL_SPEEDS
                                     ? model::twist_from_wheel_speeds(m.v_left(), m.v_right(), r.wheel_base_m)
                                     : model::Twist{m.v(), m.omega()};
      r.commanded.add({m.header().step(), twist.v, twist.omega});
    });
    setup.on<idl::PoseEstimate>("estimate/pose", [this](const idl::PoseEstimate& m) {
      RobotFigures& r = robot(m.robot_id());
      r.estimates_seen = true;
      if (m.valid() && !r.first_valid_step) {
        r.first_valid_step = m.header().step();
      }
    });
  }

  void write_robot(JsonWriter& json, std::uint32_t id) const override {
    const RobotFigures* r = robots_.find(id);
    if (r == nullptr) {
      return;
    }
    write_extremes(json, r->applied, "applied");
    write_extremes(json, r->commanded, "commanded");
    if (r->estimates_seen) {
      json.value("time_to_valid_s", r->first_valid_step ? static_cast<double>(*r->first_valid_step) * step_s_ : -1.0);
    }
  }
  void write_single_robot(JsonWriter& json, std::uint32_t id) const override { write_robot(json, id); }

 private:
  /// A robot not in the scenario (none should be) has the default body's wheel base.
  RobotFigures& robot(std::uint32_t id) {
    const auto base = wheel_base_m_.find(id);
    return robots_.get(id, step_s_, base != wheel_base_m_.end() ? base->second : model::RobotBody{}.wheel_base_m);
  }

  static void write_extremes(JsonWriter& json, const MotionExtremesTracker& t, const std::string& which) {
    if (!t.seen()) {
      return;
    }
    const MotionExtremes& e = t.extremes();
    json.value("max_abs_v_" + which + "_mps", e.max_abs_v_mps);
    json.value("max_abs_omega_" + which + "_radps", e.max_abs_omega_radps);
    json.value("max_abs_wheel_speed_" + which + "_mps", e.max_abs_wheel_speed_mps);
    json.value("max_abs_accel_" + which + "_mps2", e.max_abs_accel_mps2);
    json.value("max_abs_angular_accel_" + which + "_radps2", e.max_abs_angular_accel_radps2);
  }

  double step_s_ = 0.0;
  std::map<std::uint32_t, double> wheel_base_m_;  // robot -> m
  PerRobot<RobotFigures> robots_;
};

std::unique_ptr<MetricsModule> make_motion_module() { return std::make_unique<MotionModule>(); }

/// `robodds run`'s lines: what the plant applied (against the robot's limits) and when the
/// estimate became valid; with one robot (the keys are per robot otherwise).
Headline motion_headline() {
  return {{"applied motion", "", "max |v| {max_abs_v_applied_mps} m/s, |omega| {max_abs_omega_applied_radps} rad/s, "
                                 "|a| {max_abs_accel_applied_mps2} m/s^2"},
          {"valid estimate", "", "time to it: {time_to_valid_s} s"}};
}

}  // namespace
}  // namespace robodds::evaluator

ROBODDS_REGISTER_METRICS_MODULE(motion, "issue 12: extremes of the applied and commanded motion, time to a valid estimate", 20,
                                robodds::evaluator::make_motion_module, robodds::evaluator::motion_headline());
