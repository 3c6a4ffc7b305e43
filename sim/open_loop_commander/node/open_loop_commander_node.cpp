#include "sim/open_loop_commander/node/open_loop_commander_node.hpp"

#include <limits>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"
#include "sim/open_loop_commander/node/open_loop_commander_params.hpp"
#include "sim/open_loop_commander/open_loop_commander.hpp"

namespace robodds::open_loop_commander {
namespace {

class OpenLoopNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    const OpenLoopNodeParams node_params = read_params(p, open_loop_commander_param_table());
    const double rate_hz = node_params.rate_hz;
    params_ = node_params.profile;
    inject_nan_at_step_ = node_params.inject_nan_at_step;
    p.validate(params_);
    ctx.set_rate_hz(rate_hz, "rate_hz");
    for (const RobotSpec& robot : ctx.robots()) {
      robots_.push_back(robot.id);
    }
    out_ = &ctx.advertise<idl::VelocityCommand>("plant/cmd");
  }

  void on_step(const StepInfo& info) override {
    for (std::size_t i = 0; i < robots_.size(); ++i) {
      const TwistCommand twist = open_loop_command(params_, i, info.time_s);
      idl::VelocityCommand cmd;
      cmd.robot_id(robots_[i]);
      cmd.mode(idl::VELOCITY);
      cmd.v(twist.v);
      cmd.omega(twist.omega);
      if (inject_nan_at_step_ >= 0 && info.step == static_cast<std::uint64_t>(inject_nan_at_step_)) {
        cmd.v(std::numeric_limits<double>::quiet_NaN());  // fault injection for consumer tests
      }
      out_->publish(cmd);
    }
  }

 private:
  OpenLoopParams params_;
  std::vector<std::uint32_t> robots_;
  std::int64_t inject_nan_at_step_ = -1;
  Output<idl::VelocityCommand>* out_ = nullptr;
};

}  // namespace

std::unique_ptr<Component> make_open_loop_node() { return std::make_unique<OpenLoopNode>(); }

}  // namespace robodds::open_loop_commander

ROBODDS_REGISTER_COMPONENT(open_loop_commander, "open-loop velocity commands -> plant/cmd",
                           robodds::open_loop_commander::make_open_loop_node,
                           robodds::open_loop_commander::open_loop_commander_param_table);
