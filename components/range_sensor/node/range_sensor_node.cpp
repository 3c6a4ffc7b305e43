#include "components/range_sensor/node/range_sensor_node.hpp"

#include <map>

#include "common/random.hpp"
#include "components/range_sensor/range_model.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/base/log.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"

namespace robodds::range_sensor {
namespace {

/// One robot's stream of ranges: to its current target, announced sample by sample (next_step).
struct RobotStream {
  RobotStream(RandomEngine noise_engine, RandomEngine dropout_engine) : noise(noise_engine), dropout(dropout_engine) {}
  RandomEngine noise;
  RandomEngine dropout;
  std::uint64_t next_publish_step = 0;  // the step its last sample announced
  std::uint32_t target_id = 0;
  double target_x = 0.0;  // m, world: its current target
  double target_y = 0.0;
  bool started = false;  // has published
  bool ended = false;    // left the mission: its final sample is out
};

class RangeSensorNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    params_ = read_params(p, range_sensor_param_table());
    p.validate(params_);
    ctx.set_rate_hz(params_.rate_hz, "rate_hz");
    period_ = ctx.period_steps();
    lockstep_ = ctx.mode() == TimeMode::kLockstep;
    name_ = ctx.name();
    for (const RobotSpec& robot : ctx.robots()) {
      const std::string id = "robot" + std::to_string(robot.id);
      streams_.emplace(robot.id, RobotStream(RandomEngine(ctx.seed_for(id)), RandomEngine(ctx.seed_for(id + "/dropout"))));
    }
    truth_ = &ctx.subscribe<idl::RobotState>("plant/state", Subscription::instances(ctx.robot_keys()).newest_only());
    tasks_ = &ctx.subscribe<idl::TargetAssignment>("mission/target", Subscription::instances(ctx.robot_keys()));
    out_ = &ctx.advertise<idl::RangeMeasurement>("sensor/range");
  }

  void on_step(const StepInfo& info) override {
    for (auto& [id, stream] : streams_) {
      const idl::RobotState* state = truth_->latest(id);
      const idl::TargetAssignment* task = tasks_->latest(id);
      if (state == nullptr || task == nullptr || stream.ended) {
        continue;  // real time before the plant's or the mission's first sample; or it left
      }
      if (!task->active()) {
        if (stream.started) {
          publish(id, stream, *state, kNeverAgain);  // it leaves: the final sample of its stream
          stream.ended = true;
        } else if (lockstep_) {
          throw RunError(name_ + ": robot " + std::to_string(id) + " has no target at step " + std::to_string(info.step) +
                         " (the scenario's events must give every robot the range sensor serves a target from time 0)");
        }
        continue;
      }
      const bool new_target = !stream.started || task->target_id() != stream.target_id;
      if (!new_target && info.step < stream.next_publish_step) {
        continue;  // a lost sample (announced by the previous one's next_step)
      }
      stream.target_id = task->target_id();
      stream.target_x = task->target_x();
      stream.target_y = task->target_y();
      publish(id, stream, *state, next_publish_step(info.step, task->header().next_step(), stream));
    }
  }

 private:
  /// The next step this robot publishes at: its next due step whose sample is not lost, but at
  /// the latest the first due step at or after the mission's next change (a new target or a
  /// leave must be published when it happens).
  std::uint64_t next_publish_step(std::uint64_t step, std::uint64_t mission_next_step, RobotStream& stream) const {
    const std::uint64_t forced = mission_next_step == kNeverAgain ? kNeverAgain
                                                                  : (mission_next_step + period_ - 1) / period_ * period_;
    std::uint64_t next = step + period_;
    while (next < forced && sample_lost(params_, stream.dropout)) {
      next += period_;
    }
    return next;
  }

  void publish(std::uint32_t id, RobotStream& stream, const idl::RobotState& state, std::uint64_t next_step) {
    idl::RangeMeasurement m;
    m.robot_id(id);
    m.target_id(stream.target_id);
    m.range(measure_range(true_range(state.x(), state.y(), stream.target_x, stream.target_y), params_, stream.noise));
    m.var(params_.noise_sigma_m * params_.noise_sigma_m);
    out_->publish_next_at(m, next_step);
    stream.next_publish_step = next_step;
    stream.started = true;
  }

  RangeSensorParams params_;
  std::uint64_t period_ = 1;
  bool lockstep_ = true;
  std::string name_;
  std::map<std::uint32_t, RobotStream> streams_;
  Input<idl::RobotState>* truth_ = nullptr;
  Input<idl::TargetAssignment>* tasks_ = nullptr;
  Output<idl::RangeMeasurement>* out_ = nullptr;
};

}  // namespace

std::unique_ptr<Component> make_range_sensor_node() { return std::make_unique<RangeSensorNode>(); }

}  // namespace robodds::range_sensor

ROBODDS_REGISTER_COMPONENT(range_sensor, "noisy range to the assigned target: plant/state + mission/target -> sensor/range",
                           robodds::range_sensor::make_range_sensor_node,
                           robodds::range_sensor::range_sensor_param_table);
