#include "sim/truth_estimator/node/truth_estimator_node.hpp"

#include <limits>

#include "robodds/idl/robodds.h"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"
#include "sim/truth_estimator/node/truth_estimator_params.hpp"

namespace robodds::truth_estimator {
namespace {

class TruthEstimatorNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    const TruthEstimatorParams params = read_params(ctx.params(), truth_estimator_param_table());
    ctx.set_rate_hz(params.rate_hz, "rate_hz");
    inject_nan_at_step_ = params.inject_nan_at_step;
    keys_ = ctx.robot_keys();
    truth_ = &ctx.subscribe<idl::RobotState>("plant/state", Subscription::instances(keys_));
    out_ = &ctx.advertise<idl::PoseEstimate>("estimate/pose");
  }

  void on_step(const StepInfo& info) override {
    for (std::uint64_t key : keys_) {
      const idl::RobotState* state = truth_->latest(key);
      if (state == nullptr) {
        continue;
      }
      idl::PoseEstimate estimate;
      estimate.robot_id(state->robot_id());
      estimate.x(state->x());
      estimate.y(state->y());
      estimate.theta(state->theta());
      estimate.valid(true);
      if (inject_nan_at_step_ >= 0 && info.step == static_cast<std::uint64_t>(inject_nan_at_step_)) {
        estimate.x(std::numeric_limits<double>::quiet_NaN());  // fault injection for consumer tests
      }
      out_->publish(estimate);
    }
  }

 private:
  std::int64_t inject_nan_at_step_ = -1;
  std::vector<std::uint64_t> keys_;
  Input<idl::RobotState>* truth_ = nullptr;
  Output<idl::PoseEstimate>* out_ = nullptr;
};

}  // namespace

std::unique_ptr<Component> make_truth_estimator_node() { return std::make_unique<TruthEstimatorNode>(); }

}  // namespace robodds::truth_estimator

ROBODDS_REGISTER_COMPONENT(truth_estimator, "ideal estimator: plant/state -> estimate/pose (true pose)",
                           robodds::truth_estimator::make_truth_estimator_node,
                           robodds::truth_estimator::truth_estimator_param_table);
