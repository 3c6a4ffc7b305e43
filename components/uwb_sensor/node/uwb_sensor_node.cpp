#include "components/uwb_sensor/node/uwb_sensor_node.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/model/uwb_array.hpp"
#include "common/random.hpp"
#include "components/uwb_sensor/uwb_error_model.hpp"
#include "components/uwb_sensor/uwb_sensor_params.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"
#include "system/robot_facts.hpp"

namespace robodds::uwb_sensor {
namespace {

using RobotPair = std::pair<std::uint32_t, std::uint32_t>;

model::Pose2 pose_of(const idl::RobotState& s) { return model::Pose2{s.x(), s.y(), s.theta()}; }

class UwbSensorNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    params_ = read_params(p, uwb_sensor_param_table());
    p.validate(params_);
    ctx.set_rate_hz(params_.rate_hz, "rate_hz");
    lockstep_ = ctx.mode() == TimeMode::kLockstep;
    array_ = system::uwb_array(ctx.scenario());  // the array every robot carries: the scenario's fact
    walls_ = params_.walls();
    const auto nodes = static_cast<Eigen::Index>(array_.nodes_m.size());
    std::vector<std::uint64_t> everyone;
    for (const RobotSpec& peer : ctx.scenario().robots) {
      everyone.push_back(peer.id);
    }
    for (const RobotSpec& robot : ctx.robots()) {
      for (const RobotSpec& peer : ctx.scenario().robots) {
        if (peer.id == robot.id) {
          continue;
        }
        const std::string direction = "robot" + std::to_string(robot.id) + "/peer" + std::to_string(peer.id);
        directions_.emplace(RobotPair{robot.id, peer.id},
                            DirectionStreams{RandomEngine(ctx.seed_for(direction + "/white")),
                                             RandomEngine(ctx.seed_for(direction + "/nlos")),
                                             RandomEngine(ctx.seed_for(direction + "/loss"))});
        const RobotPair pair{std::min(robot.id, peer.id), std::max(robot.id, peer.id)};
        if (pairs_.count(pair) == 0) {
          // One link, whoever measures it: seeded by the scenario seed and the pair, not by this
          // instance's name, so that two instances serving the two robots agree (README).
          const std::string link = "uwb_sensor/pair" + std::to_string(pair.first) + "-" + std::to_string(pair.second);
          const std::uint64_t seed = ctx.scenario().seed;
          pairs_.emplace(pair, PairErrors(nodes, nodes, 0.0, params_.errors, RandomEngine(derive_seed(seed, link + "/bias")),
                                          RandomEngine(derive_seed(seed, link + "/common"))));
        }
      }
    }
    truth_ = &ctx.subscribe<idl::RobotState>("plant/state", Subscription::instances(everyone).newest_only());
    out_ = &ctx.advertise<idl::UwbRanges>("sensor/uwb");
    std::vector<std::uint64_t> keys;  // lockstep publishes every direction at every due step
    for (const auto& [direction, streams] : directions_) {
      idl::UwbRanges key;
      key.robot_id(direction.first);
      key.peer_id(direction.second);
      keys.push_back(idl::instance_key(key));
    }
    ctx.publishes_instances("sensor/uwb", std::move(keys));
  }

  void on_step(const StepInfo& info) override {
    for (auto& [direction, streams] : directions_) {  // std::map: (robot, peer) in id order
      const auto [robot, peer] = direction;
      const idl::RobotState* own = truth_->latest(robot);
      const idl::RobotState* other = truth_->latest(peer);
      if (own == nullptr || other == nullptr) {
        continue;  // real time before the plant's first samples
      }
      PairErrors& shared = pairs_.at(RobotPair{std::min(robot, peer), std::max(robot, peer)});
      shared.advance_to(info.time_s);
      // Every draw happens whatever the outcome, so that losses and range do not shift the streams.
      const bool lost = frame_lost(params_.errors, streams.loss);
      const model::Pose2 own_pose = pose_of(*own);
      const model::Pose2 other_pose = pose_of(*other);
      const Eigen::MatrixXd truth = model::array_ranges(array_, own_pose, array_, other_pose);
      const BlockedLinks blocked = links_through_walls(array_, own_pose, array_, other_pose, walls_);
      const Eigen::MatrixXd ranges = measure_ranges(truth, shared.link_bias_m(robot < peer), shared.common_m(), params_.errors,
                                                    streams.white, streams.nlos, blocked);
      const bool in_range = truth.maxCoeff() <= params_.max_range_m;
      if ((lost || !in_range) && !lockstep_) {
        continue;  // real time: nothing sent
      }
      idl::UwbRanges m;
      m.robot_id(robot);
      m.peer_id(peer);
      if (!lost && in_range) {  // else lockstep's empty sample: consumers learn there is nothing at this step
        m.rows(static_cast<std::uint32_t>(ranges.rows()));
        m.cols(static_cast<std::uint32_t>(ranges.cols()));
        std::vector<double> row_major;
        row_major.reserve(static_cast<std::size_t>(ranges.size()));
        for (Eigen::Index k = 0; k < ranges.rows(); ++k) {
          for (Eigen::Index l = 0; l < ranges.cols(); ++l) {
            row_major.push_back(ranges(k, l));
          }
        }
        m.ranges(std::move(row_major));
      }
      out_->publish(m);
    }
  }

 private:
  UwbSensorParams params_;
  bool lockstep_ = true;
  model::UwbArray array_;
  std::vector<Wall> walls_;
  std::map<RobotPair, DirectionStreams> directions_;
  std::map<RobotPair, PairErrors> pairs_;  // (lower id, higher id)
  Input<idl::RobotState>* truth_ = nullptr;
  Output<idl::UwbRanges>* out_ = nullptr;
};

}  // namespace

std::unique_ptr<Component> make_uwb_sensor_node() { return std::make_unique<UwbSensorNode>(); }

}  // namespace robodds::uwb_sensor

ROBODDS_REGISTER_COMPONENT(uwb_sensor,
                           "UWB array ranges between robots: plant/state of every robot -> sensor/uwb (robot, peer), K x L ranges",
                           robodds::uwb_sensor::make_uwb_sensor_node, robodds::uwb_sensor::uwb_sensor_param_table);
