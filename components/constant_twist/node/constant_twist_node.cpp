// A constant velocity command for every robot it serves: the example of docs/writing-a-component.md,
// made by following that page (its own folder, one add_subdirectory line, a scenario).
#include <cstdint>
#include <memory>
#include <vector>

#include "common/param_table.hpp"          // params::ParamTable, params::positive(), params::finite()
#include "robodds/idl/robodds.h"           // idl::VelocityCommand (generated from idl/robodds.idl)
#include "runtime/component/component.hpp"           // Component, ComponentContext, StepInfo, Input, Output, Subscription
#include "runtime/config/param_table_reader.hpp"  // read_params()
#include "runtime/component/registry.hpp"            // ROBODDS_REGISTER_COMPONENT

namespace robodds::constant_twist {

struct ConstantTwistParams {
  double rate_hz = 10.0;
  double v_mps = 0.5;
  double omega_radps = 0.0;
};

const params::ParamTable<ConstantTwistParams>& constant_twist_param_table() {
  static const params::ParamTable<ConstantTwistParams> table =
      params::ParamTable<ConstantTwistParams>("Constant velocity command for every served robot.")
          .add("rate_hz", &ConstantTwistParams::rate_hz, "Hz", params::positive(),
               "command rate; must divide the simulation rate")
          .add("v_mps", &ConstantTwistParams::v_mps, "m/s", params::finite(), "forward speed")
          .add("omega_radps", &ConstantTwistParams::omega_radps, "rad/s", params::finite(), "turn rate");
  return table;
}

namespace {

class ConstantTwistNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    params_ = read_params(ctx.params(), constant_twist_param_table());  // every key: type + range
    ctx.set_rate_hz(params_.rate_hz, "rate_hz");
    for (const RobotSpec& robot : ctx.robots()) {
      robots_.push_back(robot.id);
    }
    out_ = &ctx.advertise<idl::VelocityCommand>("plant/cmd");
  }

  void on_step(const StepInfo&) override {
    for (const std::uint32_t id : robots_) {  // every served robot at every due step
      idl::VelocityCommand cmd;
      cmd.robot_id(id);
      cmd.mode(idl::VELOCITY);
      cmd.v(params_.v_mps);
      cmd.omega(params_.omega_radps);
      out_->publish(cmd);  // the runtime stamps the header
    }
  }

 private:
  ConstantTwistParams params_;
  std::vector<std::uint32_t> robots_;
  Output<idl::VelocityCommand>* out_ = nullptr;
};

}  // namespace

std::unique_ptr<Component> make_constant_twist_node() { return std::make_unique<ConstantTwistNode>(); }

}  // namespace robodds::constant_twist

ROBODDS_REGISTER_COMPONENT(constant_twist, "constant velocity commands -> plant/cmd",
                           robodds::constant_twist::make_constant_twist_node,
                           robodds::constant_twist::constant_twist_param_table);
