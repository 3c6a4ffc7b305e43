// The relative estimator node on the in-memory bus: one robot (1) and two peers (2, 3) standing
// still, exact ranges (sensor/uwb) at 50 Hz and odometry at 10 Hz from a feeder; the node runs at
// 10 Hz. Checks the five stage topics and their keys, validity rules (a rejected frame, frames that
// stop), and the start-up errors that name the key.
#include "components/uwb_relative_estimator/node/uwb_relative_estimator_node.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/model/diff_drive_kinematics.hpp"
#include "common/model/uwb_array.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_test_scenario.hpp"

ROBODDS_DECLARE_COMPONENT(uwb_relative_estimator);

namespace robodds::uwb_relative_estimator {
namespace {

using robodds::testing::NodeHarness;
using robodds::testing::of_instance;
using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_uwb_relative_estimator>;

constexpr double kPi = 3.14159265358979323846;

// Robot 1 at the origin facing +y; robot 2 at (3, 4) facing -x; robot 3 at (-2, 1) facing +x
// (without `peers`: robot 1 alone).
ScenarioText scenario(const std::string& params, bool peers = true) {
  ScenarioText s("uwb_relative_estimator_node", 0.02, 2.0);
  s.robot("{id: 1, x: 0, y: 0, theta: 1.5707963267948966}");
  if (peers) {
    s.robot("{id: 2, x: 3, y: 4, theta: 3.14159265358979}").robot("{id: 3, x: -2, y: 1, theta: 0}");
  }
  return s.component("{name: estimator, type: uwb_relative_estimator, robots: [1], params: {" + params + "}}");
}

model::Pose2 world(std::uint32_t robot) {
  if (robot == 2) {
    return {3.0, 4.0, 3.14159265358979};
  }
  if (robot == 3) {
    return {-2.0, 1.0, 0.0};
  }
  return {0.0, 0.0, kPi / 2.0};
}

std::uint64_t key(std::uint32_t robot, std::uint32_t peer) { return (std::uint64_t{robot} << 32) | peer; }

/// The UwbRanges sample of `ranges` (K x L) from `robot` to `peer`, row major.
idl::UwbRanges ranges_sample(std::uint32_t robot, std::uint32_t peer, const Eigen::MatrixXd& ranges) {
  idl::UwbRanges m;
  m.robot_id(robot);
  m.peer_id(peer);
  m.rows(static_cast<std::uint32_t>(ranges.rows()));
  m.cols(static_cast<std::uint32_t>(ranges.cols()));
  std::vector<double> flat;
  for (Eigen::Index k = 0; k < ranges.rows(); ++k) {
    for (Eigen::Index l = 0; l < ranges.cols(); ++l) {
      flat.push_back(ranges(k, l));
    }
  }
  m.ranges(flat);
  return m;
}

/// Feeds odometry of standing robots every 5 steps (10 Hz) and exact ranges from robot 1 to its
/// peers, and from robot 2 to robot 3 (the peers' link), every step (50 Hz) while `frames(step)`
/// says so; every robot carries the square array of side `array_side_m`.
void feed(NodeHarness& h, std::function<bool(std::uint64_t)> frames, std::function<idl::UwbRanges(idl::UwbRanges, std::uint64_t)> edit = nullptr,
          bool with_link = true, double array_side_m = 0.5) {
  h.feed([&h, frames, edit, with_link, array_side_m](std::uint64_t step) {
    if (step % 5 == 0) {
      for (std::uint32_t robot : {1u, 2u, 3u}) {
        idl::Odometry o;
        o.robot_id(robot);
        o.dt_s(step == 0 ? 0.0 : 0.1);
        h.publish("sensor/odometry", o, step, step + 5);
      }
    }
    for (const auto& [robot, peer] : {std::pair{1u, 2u}, std::pair{1u, 3u}, std::pair{2u, 3u}}) {
      if (robot == 2 && !with_link) {
        continue;
      }
      idl::UwbRanges m;
      m.robot_id(robot);
      m.peer_id(peer);
      if (frames(step)) {
        const model::UwbArray a = model::square_array(array_side_m);
        m = ranges_sample(robot, peer, model::array_ranges(a, world(robot), a, world(peer)));
        if (edit) {
          m = edit(m, step);
        }
      }
      h.publish("sensor/uwb", m, step, step + 1);
    }
  });
}

const std::vector<const char*> kTopics = {"estimate/relative_pose", "estimate/relative_pose_uwb", "estimate/relative_pose_window",
                                          "estimate/relative_pose_pf_baseline", "estimate/relative_pose_odometry",
                                          "estimate/relative_pose_tc"};

TEST(UwbRelativeEstimatorNode, EveryStageOnItsTopicForEachPeerAtEveryEpoch) {
  Harness h(scenario(""));
  feed(h, [](std::uint64_t) { return true; });
  std::vector<const std::vector<idl::RelativePoseEstimate>*> out;
  for (const char* topic : kTopics) {
    out.push_back(&h.record<idl::RelativePoseEstimate>(topic));
  }
  h.run({"estimator"});
  const model::Pose2 truth2 = model::between(world(1), world(2));
  const model::Pose2 truth3 = model::between(world(1), world(3));
  for (std::size_t t = 0; t < kTopics.size(); ++t) {
    SCOPED_TRACE(kTopics[t]);
    const auto to2 = robodds::testing::of_instance(*out[t], key(1, 2));
    const auto to3 = robodds::testing::of_instance(*out[t], key(1, 3));
    ASSERT_EQ(to2.size(), 21u) << "10 Hz epochs at steps 0, 5, ..., 100";
    ASSERT_EQ(to3.size(), 21u);
    EXPECT_EQ(to2.back().header().step(), 100u);
    ASSERT_TRUE(to2.back().valid());
    ASSERT_TRUE(to3.back().valid());
    // The filters keep their per-epoch noise (5 mm, 3 mrad): centimetres after 20 epochs.
    EXPECT_NEAR(to2.back().x(), truth2.x, 0.05);
    EXPECT_NEAR(to2.back().y(), truth2.y, 0.05);
    EXPECT_NEAR(to3.back().theta(), truth3.theta, 0.02);
  }
  const auto uwb = robodds::testing::of_instance(*out[1], key(1, 3));
  EXPECT_NEAR(uwb.back().x(), truth3.x, 1e-4) << "exact ranges: the single-epoch solve is exact";
  const auto odometry = robodds::testing::of_instance(*out[4], key(1, 2));
  EXPECT_TRUE(odometry.front().valid()) << "the odometry stage starts from the scenario's poses";
  EXPECT_NEAR(odometry.front().x(), truth2.x, 1e-9);
}

// The estimator models the scenario's array (facts: uwb_array:), the one the sensor measures with:
// exact ranges of 0.8 m squares give an exact single-epoch solve.
TEST(UwbRelativeEstimatorNode, ModelsTheScenariosArray) {
  Harness h(scenario("").fact("uwb_array: {array_side_m: 0.8}"));
  feed(h, [](std::uint64_t) { return true; }, nullptr, true, 0.8);
  const auto& uwb = h.record<idl::RelativePoseEstimate>("estimate/relative_pose_uwb");
  h.run({"estimator"});
  const model::Pose2 truth2 = model::between(world(1), world(2));
  const auto to2 = robodds::testing::of_instance(uwb, key(1, 2));
  ASSERT_EQ(to2.size(), 21u);
  ASSERT_TRUE(to2.back().valid());
  EXPECT_NEAR(to2.back().x(), truth2.x, 1e-4) << "a 0.5 m array model would not fit these ranges";
  EXPECT_NEAR(to2.back().y(), truth2.y, 1e-4);
  EXPECT_NEAR(to2.back().theta(), truth2.theta, 1e-4);
}

TEST(UwbRelativeEstimatorNode, AFrameThatDoesNotFitTheArraysIsRejectedAndCountedNeverAnEstimate) {
  Harness h(scenario(""));
  // From step 50 on robot 1's frames to peer 3 have 4 x 3 ranges (a sensor with another array).
  feed(h, [](std::uint64_t) { return true; }, [](idl::UwbRanges m, std::uint64_t step) {
    if (m.peer_id() == 3 && step >= 50) {
      m.cols(3);
      m.ranges(std::vector<double>(12, 4.0));
    }
    return m;
  });
  const auto& uwb = h.record<idl::RelativePoseEstimate>("estimate/relative_pose_uwb");
  h.run({"estimator"});
  const auto to3 = robodds::testing::of_instance(uwb, key(1, 3));
  const auto to2 = robodds::testing::of_instance(uwb, key(1, 2));
  for (const auto& e : to3) {
    EXPECT_EQ(e.valid(), e.header().step() < 50) << "step " << e.header().step();
  }
  EXPECT_TRUE(to2.back().valid()) << "the other peer is not affected";
}

TEST(UwbRelativeEstimatorNode, NanAndNegativeRangesAreRefusedByTheInputAndNeverReachAnEstimate) {
  Harness h(scenario(""));
  // From step 50 on robot 1's frames to peer 3 carry a NaN range (odd steps) or a negative one.
  feed(h, [](std::uint64_t) { return true; }, [](idl::UwbRanges m, std::uint64_t step) {
    if (m.peer_id() == 3 && step >= 50) {
      m.ranges()[5] = step % 2 == 1 ? std::nan("") : -1.0;
    }
    return m;
  });
  const auto& uwb = h.record<idl::RelativePoseEstimate>("estimate/relative_pose_uwb");
  const auto& pf = h.record<idl::RelativePoseEstimate>("estimate/relative_pose");
  h.run({"estimator"});
  const model::Pose2 truth3 = model::between(world(1), world(3));
  // The epoch of step 50 still has the good frame of step 49 (its newest accepted one).
  for (const auto& e : robodds::testing::of_instance(uwb, key(1, 3))) {
    EXPECT_EQ(e.valid(), e.header().step() <= 50) << "step " << e.header().step();
    EXPECT_TRUE(std::isfinite(e.x()) && std::isfinite(e.y()) && std::isfinite(e.theta()));
  }
  const auto last = robodds::testing::of_instance(pf, key(1, 3)).back();
  EXPECT_NEAR(last.x(), truth3.x, 0.1) << "the filter was never fed a bad frame";
  EXPECT_TRUE(robodds::testing::of_instance(uwb, key(1, 2)).back().valid()) << "the other peer is not affected";
}

TEST(UwbRelativeEstimatorNode, WhenAPeersFramesStopItsFrameStagesBecomeInvalidAfterTheTimeout) {
  Harness h(scenario("uwb_timeout_s: 0.5"));
  // Frames until 0.78 s: the epoch of 0.8 s takes the last one (an epoch's newest frame).
  feed(h, [](std::uint64_t step) { return step < 40; });
  const auto& pf = h.record<idl::RelativePoseEstimate>("estimate/relative_pose");
  const auto& odometry = h.record<idl::RelativePoseEstimate>("estimate/relative_pose_odometry");
  h.run({"estimator"});
  for (const auto& e : robodds::testing::of_instance(pf, key(1, 2))) {
    const double t = static_cast<double>(e.header().step()) * 0.02;
    if (t > 0.1 && t <= 0.8 + 0.5 + 1e-9) {
      EXPECT_TRUE(e.valid()) << "t " << t << ": the last frame (epoch 0.8 s) is recent enough";
    } else if (t > 1.3 + 1e-9) {
      EXPECT_FALSE(e.valid()) << "t " << t << ": no frame for more than 0.5 s";
    }
  }
  EXPECT_TRUE(robodds::testing::of_instance(odometry, key(1, 2)).back().valid()) << "odometry needs no frame";
}

TEST(UwbRelativeEstimatorNode, WithPeerLinksTheEstimatorWaitsForThePeersStreamAndNamesIt) {
  {
    Harness h(scenario(""));
    h.options().input_timeout_s = 0.3;
    feed(h, [](std::uint64_t) { return true; }, nullptr, /*with_link=*/false);
    const std::string error = h.run_error<RunError>({"estimator"});
    EXPECT_NE(error.find("sensor/uwb, robot_id=2 peer_id=3"), std::string::npos) << error;
  }
  Harness h(scenario("peer_links: false"));
  h.options().input_timeout_s = 0.3;
  feed(h, [](std::uint64_t) { return true; }, nullptr, /*with_link=*/false);
  const auto& pf = h.record<idl::RelativePoseEstimate>("estimate/relative_pose");
  EXPECT_EQ(h.run_error<RunError>({"estimator"}), "") << "peer_links: false needs only the robot's own ranges";
  EXPECT_TRUE(robodds::testing::of_instance(pf, key(1, 3)).back().valid());
}

// Three robots driving circles (exact odometry at 10 Hz, exact ranges at 50 Hz in all four streams
// (1,2), (1,3), (2,1), (2,3)); ONE estimator serves robots 1 and 2 with peers [3, 2, 1]: robot 1
// estimates 3 and 2 (link 3-2 from the stream (2,3), transposed), robot 2 estimates 3 and 1 (link
// 3-1 from (1,3), transposed), and the streams (1,3), (2,3) serve both robots.
TEST(UwbRelativeEstimatorNode, TwoServedRobotsThatMoveSharedStreamsAndTransposedLinks) {
  Harness h(ScenarioText("uwb_relative_estimator_moving", 0.02, 3.0)
                .robot("{id: 1, x: 0, y: 0, theta: 0}")
                .robot("{id: 2, x: 4, y: 1, theta: 1}")
                .robot("{id: 3, x: -3, y: 2, theta: -2}")
                .component("{name: estimator, type: uwb_relative_estimator, robots: [1, 2], params: {peers: [3, 2, 1]}}"));
  const std::map<std::uint32_t, model::Twist> twist{{1, {0.2, 0.1}}, {2, {0.15, -0.05}}, {3, {0.1, 0.2}}};
  const std::map<std::uint32_t, model::Pose2> start{{1, {0, 0, 0}}, {2, {4, 1, 1}}, {3, {-3, 2, -2}}};
  const auto pose_at = [&](std::uint32_t robot, std::uint64_t step) {
    return model::integrate_exact(start.at(robot), twist.at(robot), 0.02 * static_cast<double>(step));
  };
  h.feed([&](std::uint64_t step) {
    if (step % 5 == 0) {
      for (std::uint32_t robot : {1u, 2u, 3u}) {
        idl::Odometry o;
        o.robot_id(robot);
        o.v(twist.at(robot).v);
        o.omega(twist.at(robot).omega);
        o.dt_s(step == 0 ? 0.0 : 0.1);
        h.publish("sensor/odometry", o, step, step + 5);
      }
    }
    for (const auto& [robot, peer] : {std::pair{1u, 2u}, std::pair{1u, 3u}, std::pair{2u, 1u}, std::pair{2u, 3u}}) {
      const model::UwbArray a = model::square_array(0.5);
      h.publish("sensor/uwb", ranges_sample(robot, peer, model::array_ranges(a, pose_at(robot, step), a, pose_at(peer, step))), step,
                step + 1);
    }
  });
  std::vector<const std::vector<idl::RelativePoseEstimate>*> out;
  for (const char* topic : kTopics) {
    out.push_back(&h.record<idl::RelativePoseEstimate>(topic));
  }
  h.run({"estimator"});
  for (const auto& [robot, peer] : {std::pair{1u, 3u}, std::pair{1u, 2u}, std::pair{2u, 3u}, std::pair{2u, 1u}}) {
    const model::Pose2 truth = model::between(pose_at(robot, 150), pose_at(peer, 150));
    for (std::size_t t = 0; t < kTopics.size(); ++t) {
      const auto samples = robodds::testing::of_instance(*out[t], key(robot, peer));
      ASSERT_EQ(samples.size(), 31u) << kTopics[t] << " " << robot << "->" << peer;
      const auto& last = samples.back();
      EXPECT_TRUE(last.valid()) << kTopics[t] << " " << robot << "->" << peer;
      // Exact inputs: the solves, the window and dead reckoning are exact; the filters keep their noise.
      const double tolerance = t == 0 || t == 3 ? 0.1 : 1e-3;
      EXPECT_NEAR(last.x(), truth.x, tolerance) << kTopics[t] << " " << robot << "->" << peer;
      EXPECT_NEAR(last.y(), truth.y, tolerance) << kTopics[t] << " " << robot << "->" << peer;
    }
  }
}

std::string start_error(const std::string& yaml) {
  Harness h(yaml);
  return h.run_error<ConfigError>({"estimator"});
}

TEST(UwbRelativeEstimatorNode, BadSetUpsAreStartUpErrorsNamingTheKey) {
  EXPECT_NE(start_error(scenario("peers: [2, 9]")).find("peers: robot 9 is not in the scenario"), std::string::npos)
      << start_error(scenario("peers: [2, 9]"));
  EXPECT_NE(start_error(scenario("", /*peers=*/false)).find("has no peer"), std::string::npos);
  EXPECT_NE(start_error(scenario("window_epochs: 1")).find("window_epochs"), std::string::npos);
  EXPECT_NE(start_error(scenario("pf.num_particles: 0")).find("pf.num_particles"), std::string::npos);
  EXPECT_NE(start_error(scenario("peers: [2, 2]")).find("robot 2 is listed twice"), std::string::npos);
  // The array is the scenario's fact (facts: uwb_array:), read and checked by the estimator at configure.
  std::string error = start_error(scenario("").fact("uwb_array: {nodes_m: [[0.3, 0], [-0.3, 0]]}"));
  EXPECT_NE(error.find("facts.uwb_array: nodes_m: needs at least 3 nodes"), std::string::npos) << error;
  error = start_error(scenario("").fact("uwb_array: {nodes_m: [[0.3, 0], [-0.3, 0], [0.3, 0]]}"));
  EXPECT_NE(error.find("facts.uwb_array: nodes_m: nodes 0 and 2 coincide"), std::string::npos) << error;
  error = start_error(scenario("array_side_m: 0.5"));
  EXPECT_NE(error.find("array_side_m"), std::string::npos) << "no longer a parameter of the estimator: " << error;
}

}  // namespace
}  // namespace robodds::uwb_relative_estimator
