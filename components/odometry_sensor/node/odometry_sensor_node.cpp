#include "components/odometry_sensor/node/odometry_sensor_node.hpp"

#include <map>

#include "common/random.hpp"
#include "components/odometry_sensor/odometry_model.hpp"
#include "components/odometry_sensor/twist_accumulator.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"
#include "system/robot_facts.hpp"

namespace robodds::odometry_sensor {
namespace {

class OdometrySensorNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    params_ = read_params(p, odometry_sensor_param_table());
    p.validate(params_);
    ctx.set_rate_hz(params_.rate_hz, "rate_hz");
    for (const RobotSpec& robot : ctx.robots()) {
      robots_.emplace(robot.id, Robot{RandomEngine(ctx.seed_for("robot" + std::to_string(robot.id))), TwistAccumulator{}, SlipWander{},
                                      system::robot_body(ctx.scenario(), robot.id).wheel_base_m});
    }
    truth_ = &ctx.subscribe<idl::RobotState>("plant/state", Subscription::instances(ctx.robot_keys()));
    out_ = &ctx.advertise<idl::Odometry>("sensor/odometry");
    step_s_ = ctx.step_s();
  }

  void on_step(const StepInfo&) override {
    for (auto& [id, robot] : robots_) {
      // Each state carries the twist applied over its own step(s): sum them into wheel travel.
      for (const idl::RobotState& state : truth_->take_new(id)) {
        const double covered_s = static_cast<double>(state.header().next_step() - state.header().step()) * step_s_;
        robot.travel.add(model::Twist{state.v(), state.omega()}, covered_s);
      }
      const double covered_s = robot.travel.elapsed_s();
      // Draw order per reading: the wander's step over this interval, then the wheel noise (inside
      // measure_odometry); with the wander off it draws nothing, so the stream is what it was.
      advance_slip_wander(robot.wander, covered_s, params_, robot.engine);
      const OdometryReading reading = measure_odometry(robot.travel.mean(), covered_s, robot.wheel_base_m, params_, robot.engine, robot.wander);
      robot.travel.reset();
      idl::Odometry m;
      m.robot_id(id);
      m.v(reading.v);
      m.omega(reading.omega);
      m.dt_s(reading.dt_s);
      m.var_v(reading.var_v);
      m.var_omega(reading.var_omega);
      out_->publish(m);
    }
  }

 private:
  struct Robot {
    RandomEngine engine;
    TwistAccumulator travel;  // true twist since the last reading
    SlipWander wander;        // the wandering part of the slips (uneven floor)
    double wheel_base_m;      // m, the robot's body (shared fact robot_body)
  };

  OdometryParams params_;
  std::map<std::uint32_t, Robot> robots_;
  Input<idl::RobotState>* truth_ = nullptr;
  Output<idl::Odometry>* out_ = nullptr;
  double step_s_ = 0.01;
};

}  // namespace

std::unique_ptr<Component> make_odometry_sensor_node() { return std::make_unique<OdometrySensorNode>(); }

}  // namespace robodds::odometry_sensor

ROBODDS_REGISTER_COMPONENT(odometry_sensor, "wheel odometry with noise and slip: plant/state -> sensor/odometry",
                           robodds::odometry_sensor::make_odometry_sensor_node,
                           robodds::odometry_sensor::odometry_sensor_param_table);
