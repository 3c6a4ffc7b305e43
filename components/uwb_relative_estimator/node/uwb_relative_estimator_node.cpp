// Adapter: UwbRanges + Odometry -> RelativeEstimator -> RelativePoseEstimate per stage.
#include "components/uwb_relative_estimator/node/uwb_relative_estimator_node.hpp"

#include <algorithm>
#include <cmath>
#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/model/diff_drive_kinematics.hpp"
#include "components/uwb_relative_estimator/node/uwb_relative_estimator_params.hpp"
#include "components/uwb_relative_estimator/relative_estimator.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/log.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"
#include "system/robot_facts.hpp"

namespace robodds::uwb_relative_estimator {
namespace {

std::uint64_t pair_key(std::uint32_t robot, std::uint32_t peer) { return (std::uint64_t{robot} << 32) | peer; }

/// The topic of each stage, in Stage order.
constexpr std::array<const char*, kStageCount> kStageTopics = {
    "estimate/relative_pose_uwb", "estimate/relative_pose_window", "estimate/relative_pose",
    "estimate/relative_pose_pf_baseline", "estimate/relative_pose_odometry", "estimate/relative_pose_tc"};

/// Stages that rest on UWB frames (invalid when a peer's frames are older than uwb_timeout_s).
bool uses_frames(Stage s) {
  return s == Stage::kWindow || s == Stage::kPf || s == Stage::kPfBaseline || s == Stage::kTc;
}

/// The stages whose covariance the estimated range noise sizes (tc fits the raw ranges with its
/// own model; odometry takes none).
bool uses_range_noise(Stage s) { return s != Stage::kOdometry && s != Stage::kTc; }

class UwbRelativeEstimatorNode : public Component {
 public:
  void configure(ComponentContext& ctx) override {
    auto& p = ctx.params();
    params_ = read_params(p, relative_estimator_node_param_table());
    p.validate(params_);
    ctx.set_rate_hz(params_.rate_hz, "rate_hz");
    ctx.require_longer_than_period("uwb_timeout_s", params_.uwb_timeout_s);
    ctx.require_longer_than_period("odometry_timeout_s", params_.odometry_timeout_s);
    name_ = ctx.name();
    realtime_ = ctx.mode() == TimeMode::kRealtime;
    const model::UwbArray array = system::uwb_array(ctx.scenario());  // the one the sensor measures with
    const Scenario& scenario = ctx.scenario();
    std::vector<std::uint64_t> uwb_keys;
    std::vector<std::uint64_t> published;  // (robot, peer) keys of the estimates, for ctx.publishes_instances
    std::set<std::uint64_t> odometry_ids;
    for (const RobotSpec& robot : ctx.robots()) {
      if (robots_.count(robot.id) != 0) {
        p.fail("robots: robot " + std::to_string(robot.id) + " is served twice by " + name_);
      }
      std::vector<PeerSetup> setups;
      for (const std::uint32_t peer : peer_ids(p, scenario, robot.id)) {
        const RobotSpec& other = scenario.robot(peer);
        std::optional<model::Pose2> start;
        if (params_.odometry_known_start) {
          start = model::between(model::Pose2{robot.x, robot.y, robot.theta}, model::Pose2{other.x, other.y, other.theta});
        }
        setups.push_back(PeerSetup{peer, array, start});
        uwb_keys.push_back(pair_key(robot.id, peer));
        published.push_back(pair_key(robot.id, peer));
        odometry_ids.insert(peer);
      }
      if (params_.peer_links) {
        for (std::size_t a = 0; a < setups.size(); ++a) {
          for (std::size_t b = a + 1; b < setups.size(); ++b) {
            const std::uint32_t low = std::min(setups[a].id, setups[b].id);
            const std::uint32_t high = std::max(setups[a].id, setups[b].id);
            uwb_keys.push_back(pair_key(low, high));
          }
        }
      }
      odometry_ids.insert(robot.id);
      try {
        robots_.emplace(robot.id, RobotEstimator{RelativeEstimator(array, setups, params_.estimator,
                                                                   ctx.seed_for("robot" + std::to_string(robot.id))),
                                                 std::vector<std::optional<double>>(setups.size())});
      } catch (const std::invalid_argument& e) {
        p.fail(e.what());
      }
    }
    // What the epochs assume of the sensors (checked against the scenario's sensors before the run):
    // a frame and an odometry sample per epoch at least, and frames within uwb_timeout_s.
    std::vector<std::uint32_t> measured;  // robots whose UWB sensors measure the pairs read
    for (const std::uint64_t key : uwb_keys) {
      measured.push_back(static_cast<std::uint32_t>(key >> 32));
    }
    std::vector<std::uint32_t> moving;  // robots whose odometry is read
    for (const std::uint64_t id : odometry_ids) {
      moving.push_back(static_cast<std::uint32_t>(id));
    }
    ctx.expects_rate_of("sensor/uwb", "rate_hz", InputRateAssumption::Kind::kAtLeastMyRate, measured);
    ctx.expects_rate_of("sensor/odometry", "rate_hz", InputRateAssumption::Kind::kAtLeastMyRate, moving);
    ctx.limits_age_of("sensor/uwb", "uwb_timeout_s", params_.uwb_timeout_s, /*realtime_only=*/false, measured);
    ctx.limits_age_of("sensor/odometry", "odometry_timeout_s", params_.odometry_timeout_s, /*realtime_only=*/true, moving);
    std::sort(uwb_keys.begin(), uwb_keys.end());
    uwb_keys.erase(std::unique(uwb_keys.begin(), uwb_keys.end()), uwb_keys.end());  // links shared by robots
    ranges_ = &ctx.subscribe<idl::UwbRanges>("sensor/uwb", Subscription::instances(uwb_keys));
    odometry_ = &ctx.subscribe<idl::Odometry>("sensor/odometry",
                                              Subscription::instances({odometry_ids.begin(), odometry_ids.end()}));
    for (std::size_t s = 0; s < kStageCount; ++s) {
      outputs_[s] = &ctx.advertise<idl::RelativePoseEstimate>(kStageTopics[s]);
      ctx.publishes_instances(kStageTopics[s], published);  // every stage of every peer, every epoch
    }
    for (const std::uint64_t id : odometry_ids) {
      increments_[static_cast<std::uint32_t>(id)] = model::Pose2{};
    }
    times_ = &ctx.compute_times();
  }

  void on_step(const StepInfo& info) override {
    collect_odometry();
    frames_.clear();
    for (auto& [id, robot] : robots_) {
      estimate(id, robot, info.time_s);
    }
    for (auto& [id, increment] : increments_) {
      increment = model::Pose2{};
    }
  }

 private:
  struct RobotEstimator {
    RelativeEstimator estimator;
    std::vector<std::optional<double>> last_frame_s;  // per peer: time of the last accepted frame
  };

  /// The peers of robot `id`: the `peers` parameter (each must be a scenario robot), or every
  /// other robot of the scenario. ConfigError naming the key otherwise.
  std::vector<std::uint32_t> peer_ids(ParamReader& p, const Scenario& scenario, std::uint32_t id) const {
    std::vector<std::uint32_t> out;
    if (params_.peers.empty()) {
      for (const RobotSpec& other : scenario.robots) {
        if (other.id != id) {
          out.push_back(other.id);
        }
      }
    } else {
      for (const double peer : params_.peers) {
        const auto peer_id = static_cast<std::uint32_t>(peer);
        const bool known = std::any_of(scenario.robots.begin(), scenario.robots.end(),
                                       [&](const RobotSpec& r) { return r.id == peer_id; });
        if (!known) {
          p.fail("peers: robot " + std::to_string(peer_id) + " is not in the scenario");
        }
        if (peer_id != id) {
          out.push_back(peer_id);
        }
      }
    }
    if (out.empty()) {
      p.fail("peers: robot " + std::to_string(id) + " has no peer to estimate (the scenario needs at least two robots)");
    }
    return out;
  }

  /// Each robot's motion since the last epoch, from its odometry samples (v, omega over dt_s).
  void collect_odometry() {
    for (auto& [id, increment] : increments_) {
      for (const idl::Odometry& o : odometry_->take_new(id)) {
        if (o.dt_s() > 0.0) {
          increment = model::integrate_exact(increment, model::Twist{o.v(), o.omega()}, o.dt_s());
        }
      }
    }
  }

  /// The newest non-empty frame of this epoch from `robot` to `peer` (an empty lockstep sample
  /// means lost or out of range), read once per epoch and kept for every served robot that uses it.
  const std::optional<Eigen::MatrixXd>& newest_frame(std::uint32_t robot, std::uint32_t peer) {
    const std::uint64_t key = pair_key(robot, peer);
    if (const auto it = frames_.find(key); it != frames_.end()) {
      return it->second;
    }
    std::optional<Eigen::MatrixXd>& frame = frames_[key];
    for (const idl::UwbRanges& m : ranges_->take_new(key)) {
      if (m.rows() == 0 || m.cols() == 0) {
        continue;
      }
      Eigen::MatrixXd r(m.rows(), m.cols());
      for (Eigen::Index k = 0; k < r.rows(); ++k) {
        for (Eigen::Index l = 0; l < r.cols(); ++l) {
          r(k, l) = m.ranges()[static_cast<std::size_t>(k * r.cols() + l)];
        }
      }
      frame = std::move(r);
    }
    return frame;
  }

  void estimate(std::uint32_t id, RobotEstimator& robot, double time_s) {
    const std::vector<PeerSetup>& setups = robot.estimator.peers();
    std::vector<PeerEpoch> inputs;
    inputs.reserve(setups.size());
    for (const PeerSetup& peer : setups) {
      inputs.push_back(PeerEpoch{increments_.at(peer.id), newest_frame(id, peer.id)});
    }
    std::vector<std::optional<Eigen::MatrixXd>> links;
    if (params_.peer_links) {
      for (const PeerLink& link : robot.estimator.links()) {
        const std::uint32_t a = setups[link.first].id;
        const std::uint32_t b = setups[link.second].id;
        std::optional<Eigen::MatrixXd> frame = newest_frame(std::min(a, b), std::max(a, b));
        if (frame && a > b) {
          frame->transposeInPlace();  // measured by b: rows are b's nodes; the link wants a's first
        }
        links.push_back(std::move(frame));
      }
    }
    EpochResult result;
    {
      // One robot's whole epoch (every peer, every stage): the "cycle"; the stages' own
      // times come from the library (wall clock around each stage).
      ScopedComputeTimer cycle(*times_, "cycle");
      result = robot.estimator.step(time_s, increments_.at(id), inputs, links);
    }
    for (std::size_t s = 0; s < kStageCount; ++s) {
      times_->add_ms(stage_name(static_cast<Stage>(s)), result.stage_ms[s]);
    }
    for (std::size_t k = 0; k < setups.size(); ++k) {
      const PeerResult& peer = result.peers[k];
      if (peer.had_ranges && peer.uwb_status != TrackStatus::kRejected) {
        robot.last_frame_s[k] = time_s;
      } else if (peer.had_ranges && !warned_rejected_) {
        log::warn(name_, "robot " + std::to_string(id) + " peer " + std::to_string(setups[k].id) +
                             ": UWB frame rejected: " + peer.uwb_reason + " (logged once; counted)");
        warned_rejected_ = true;
      }
      const bool frames_fresh = robot.last_frame_s[k] && time_s - *robot.last_frame_s[k] <= params_.uwb_timeout_s;
      const bool odometry_fresh = !realtime_ || (odometry_->fresh(id, params_.odometry_timeout_s) &&
                                                 odometry_->fresh(setups[k].id, params_.odometry_timeout_s));
      for (std::size_t s = 0; s < kStageCount; ++s) {
        const StageEstimate& stage = peer.stages[s];
        const auto kind = static_cast<Stage>(s);
        const bool valid = stage.valid && (odometry_fresh || kind == Stage::kUwb) && (frames_fresh || !uses_frames(kind));
        // The range noise sizes the range errors in these stages' covariances (issue 27).
        const double range_noise_std_m = uses_range_noise(kind) ? robot.estimator.range_noise_std_m(k) : 0.0;
        publish(*outputs_[s], id, setups[k].id, stage, valid, range_noise_std_m);
      }
    }
  }

  static void publish(Output<idl::RelativePoseEstimate>& out, std::uint32_t robot, std::uint32_t peer,
                      const StageEstimate& stage, bool valid, double range_noise_std_m) {
    idl::RelativePoseEstimate m;
    m.robot_id(robot);
    m.peer_id(peer);
    // A failed solve may leave a non-finite pose: such a sample would be rejected by every reader
    // (and leave a lockstep step without this instance's sample), so it goes out as zeros, invalid.
    const bool finite = std::isfinite(stage.pose.x) && std::isfinite(stage.pose.y) && std::isfinite(stage.pose.theta) &&
                        stage.covariance.allFinite();
    if (finite) {
      m.x(stage.pose.x);
      m.y(stage.pose.y);
      m.theta(stage.pose.theta);
      for (int i = 0; i < 9; ++i) {
        m.cov()[static_cast<std::size_t>(i)] = stage.covariance(i / 3, i % 3);
      }
    }
    m.valid(valid && finite);
    m.range_noise_std_m(range_noise_std_m);
    out.publish(m);
  }

  RelativeEstimatorNodeParams params_;
  std::string name_;
  bool realtime_ = false;
  bool warned_rejected_ = false;
  std::map<std::uint32_t, RobotEstimator> robots_;
  std::map<std::uint64_t, std::optional<Eigen::MatrixXd>> frames_;  // this epoch's, by (robot, peer) key
  std::map<std::uint32_t, model::Pose2> increments_;  // per robot (served and peers): motion since the last epoch
  Input<idl::UwbRanges>* ranges_ = nullptr;
  Input<idl::Odometry>* odometry_ = nullptr;
  std::array<Output<idl::RelativePoseEstimate>*, kStageCount> outputs_{};
  ComputeTimes* times_ = nullptr;  // this component's (ctx.compute_times()): summary.json run.timing
};

}  // namespace

std::unique_ptr<Component> make_uwb_relative_estimator_node() { return std::make_unique<UwbRelativeEstimatorNode>(); }

}  // namespace robodds::uwb_relative_estimator

ROBODDS_REGISTER_COMPONENT(uwb_relative_estimator,
                           "paper 3 relative poses of peers: sensor/uwb + sensor/odometry -> estimate/relative_pose (pf) and "
                           "_uwb, _window, _pf_baseline, _odometry",
                           robodds::uwb_relative_estimator::make_uwb_relative_estimator_node,
                           robodds::uwb_relative_estimator::relative_estimator_node_param_table);
