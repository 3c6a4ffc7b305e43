#include "components/position_sensor/node/position_sensor_node.hpp"

#include <map>

#include "common/random.hpp"
#include "components/position_sensor/position_model.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"

namespace robodds::position_sensor {
namespace {

class PositionSensorNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    params_ = read_params(p, position_sensor_param_table());
    p.validate(params_);
    ctx.set_rate_hz(params_.rate_hz, "rate_hz");
    for (const RobotSpec& robot : ctx.robots()) {
      engines_.emplace(robot.id, RandomEngine(ctx.seed_for("robot" + std::to_string(robot.id))));
    }
    truth_ = &ctx.subscribe<idl::RobotState>("plant/state", Subscription::instances(ctx.robot_keys()).newest_only());
    out_ = &ctx.advertise<idl::PositionMeasurement>("sensor/position");
  }

  void on_step(const StepInfo&) override {
    for (auto& [id, engine] : engines_) {
      const idl::RobotState* state = truth_->latest(id);
      if (state == nullptr) {
        continue;  // real time before the plant's first sample
      }
      const PositionFix fix = measure_position(model::Pose2{state->x(), state->y(), state->theta()}, params_, engine);
      idl::PositionMeasurement m;
      m.robot_id(id);
      m.x(fix.x);
      m.y(fix.y);
      m.var_x(fix.var_x);
      m.var_y(fix.var_y);
      out_->publish(m);
    }
  }

 private:
  PositionSensorParams params_;
  std::map<std::uint32_t, RandomEngine> engines_;
  Input<idl::RobotState>* truth_ = nullptr;
  Output<idl::PositionMeasurement>* out_ = nullptr;
};

}  // namespace

std::unique_ptr<Component> make_position_sensor_node() { return std::make_unique<PositionSensorNode>(); }

}  // namespace robodds::position_sensor

ROBODDS_REGISTER_COMPONENT(position_sensor, "noisy absolute position: plant/state -> sensor/position",
                           robodds::position_sensor::make_position_sensor_node,
                           robodds::position_sensor::position_sensor_param_table);
