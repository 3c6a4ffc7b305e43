#include "sim/target_mission/node/target_mission_node.hpp"

#include <algorithm>
#include <vector>

#include "common/model/target_plan.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"
#include "system/mission_plan.hpp"

namespace robodds::target_mission {
namespace {

/// The component has no parameters: its mission is the scenario's `targets:` and `events:`.
struct TargetMissionParams {};

const params::ParamTable<TargetMissionParams>& target_mission_param_table() {
  static const params::ParamTable<TargetMissionParams> table = params::ParamTable<TargetMissionParams>(
      "Publishes each served robot's target task (paper 2) from the scenario's `targets:` and `events:`\n"
      "on mission/target (transient local): at step 0 and at every event step. No parameters.");
  return table;
}

class TargetMissionNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    read_params(ctx.params(), target_mission_param_table());
    plan_ = system::target_plan(ctx.scenario());
    if (plan_.empty()) {
      throw ConfigError(ctx.scenario().file + ": the target_mission component needs the scenario's 'targets:' and 'events:'");
    }
    step_s_ = ctx.step_s();
    change_steps_ = plan_.change_steps(step_s_);
    if (change_steps_.front() != 0) {
      change_steps_.insert(change_steps_.begin(), 0);  // every robot's task (maybe none) from step 0
    }
    for (const RobotSpec& robot : ctx.robots()) {
      robots_.push_back(robot.id);
    }
    out_ = &ctx.advertise<idl::TargetAssignment>("mission/target");
  }

  void on_step(const StepInfo& info) override {
    if (next_change_ >= change_steps_.size() || info.step < change_steps_[next_change_]) {
      return;
    }
    // Every task is published at each change, changed or not: one sample per robot per event step.
    ++next_change_;
    const std::uint64_t next_step = next_change_ < change_steps_.size() ? change_steps_[next_change_] : kNeverAgain;
    for (const auto& [id, task] : plan_.tasks_at(info.step, step_s_, robots_)) {
      idl::TargetAssignment a;
      a.robot_id(id);
      a.active(task.active);
      a.target_id(task.target_id);
      a.target_x(task.target_x);
      a.target_y(task.target_y);
      a.desired_radius(task.radius_m);
      a.slot(task.slot);
      a.team_size(task.team_size);
      out_->publish_next_at(a, next_step);
    }
  }

 private:
  model::TargetPlan plan_;
  double step_s_ = 0.0;
  std::vector<std::uint64_t> change_steps_;
  std::size_t next_change_ = 0;
  std::vector<std::uint32_t> robots_;
  Output<idl::TargetAssignment>* out_ = nullptr;
};

}  // namespace

std::unique_ptr<Component> make_target_mission_node() { return std::make_unique<TargetMissionNode>(); }

}  // namespace robodds::target_mission

ROBODDS_REGISTER_COMPONENT(target_mission, "publishes paper 2's target tasks from the scenario's events -> mission/target",
                           robodds::target_mission::make_target_mission_node,
                           robodds::target_mission::target_mission_param_table);
