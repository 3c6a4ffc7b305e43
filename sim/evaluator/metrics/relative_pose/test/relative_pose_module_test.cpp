// The relative pose module (paper 3) in the evaluator on the in-memory bus.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "common/angle.hpp"
#include "common/model/pose2.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/testing/node_harness.hpp"
#include "sim/evaluator/test/evaluator_test_support.hpp"

namespace robodds::evaluator {
namespace {

using robodds::testing::NodeHarness;
using namespace robodds::evaluator::testing;

// Paper 3: relative pose topics keyed (robot_id, peer_id). Three robots, the evaluator serving
// robots 1 and 2: pairs (1,2), (1,3), (2,1), (2,3). Robot 1 stands at the origin facing +x,
// robot 2 drives along +x facing +y (x = 2 + 0.25 step), robot 3 stands at (0, 3) facing -x.
// Stage pf: each pair's estimate is the truth shifted by 0.5, 1, 1.5, 2 m along x in robot i's
// frame and 0.1 rad in heading, 100 m off before metrics_after_s (0.5 s = step 5); pair (1,3)
// sends a NaN valid estimate at step 6. Stage uwb: the truth, valid at odd steps only.
const char* kRelativeScenario = R"(name: evaluator_relative
step_s: 0.1
duration_s: 1.0
seed: 1
robots:
  - {id: 1}
  - {id: 2}
  - {id: 3}
components:
  - {name: evaluator, type: evaluator, robots: [1, 2], params: {topics: [estimate/relative_pose, plant/state,
     estimate/relative_pose_uwb], metrics_after_s: 0.5}}
)";

model::Pose2 world_pose(std::uint32_t robot, std::uint64_t step) {
  if (robot == 1) {
    return {0.0, 0.0, 0.0};
  }
  if (robot == 2) {
    return {2.0 + 0.25 * static_cast<double>(step), 0.0, kPi / 2};
  }
  return {0.0, 3.0, kPi};
}

double pf_offset_m(std::uint32_t robot, std::uint32_t peer) {
  return robot == 1 ? (peer == 2 ? 0.5 : 1.0) : (peer == 1 ? 1.5 : 2.0);
}

/// `pf_valid`: the pf stage's estimates are valid (else none is).
void feed_relative(NodeHarness& h, bool pf_valid = true) {
  h.feed([&h, pf_valid](std::uint64_t step) {
    for (std::uint32_t robot : {1u, 2u, 3u}) {
      const model::Pose2 pose = world_pose(robot, step);
      idl::RobotState s;
      s.robot_id(robot);
      s.x(pose.x);
      s.y(pose.y);
      s.theta(pose.theta);
      h.publish("plant/state", s, step, step + 1);
    }
    for (std::uint32_t robot : {1u, 2u}) {
      for (std::uint32_t peer : {1u, 2u, 3u}) {
        if (peer == robot) {
          continue;
        }
        const model::Pose2 truth = model::between(world_pose(robot, step), world_pose(peer, step));
        idl::RelativePoseEstimate e;
        e.robot_id(robot);
        e.peer_id(peer);
        e.x(truth.x + pf_offset_m(robot, peer) + (step < 5 ? 100.0 : 0.0));
        e.y(truth.y);
        e.theta(truth.theta + 0.1);
        e.valid(pf_valid);
        e.range_noise_std_m(0.125 * peer);  // m; last per pair: 0.25, 0.375, 0.125, 0.375
        if (robot == 1 && peer == 3 && step == 6) {
          e.x(std::numeric_limits<double>::quiet_NaN());
        }
        h.publish("estimate/relative_pose", e, step, step + 1);
        e.x(truth.x);
        e.theta(truth.theta);
        e.valid(step % 2 == 1);
        e.range_noise_std_m(0.0);  // this stage estimates none
        h.publish("estimate/relative_pose_uwb", e, step, step + 1);
      }
    }
  });
}

/// The number after "<key>": in the "<stage>" object of summary.json's "stages"; NaN if absent.
double stage_value(const std::string& summary, const std::string& stage, const std::string& key) {
  std::smatch m;
  const std::regex pattern("\"stages\": \\{[^]*?\"" + stage + "\": \\{[^}]*\"" + key + "\": ([-0-9.e+]+)");
  return std::regex_search(summary, m, pattern) ? std::stod(m[1]) : std::numeric_limits<double>::quiet_NaN();
}

TEST(EvaluatorNode, RecordsRelativePosesWithTheirTruthAndWritesTheStageErrors) {
  NodeHarness h(kRelativeScenario);
  add_evaluator(h);
  feed_relative(h);
  h.run({"evaluator"});

  // pf: steps 5..10 of 4 pairs, but the NaN sample of (1,3) at step 6 (rejected by the input).
  std::vector<double> errors;
  for (std::uint32_t robot : {1u, 2u}) {
    for (std::uint32_t peer : {1u, 2u, 3u}) {
      for (int step = 5; step <= 10 && peer != robot; ++step) {
        if (!(robot == 1 && peer == 3 && step == 6)) {
          errors.push_back(pf_offset_m(robot, peer));
        }
      }
    }
  }
  double mean = 0.0;
  for (double e : errors) {
    mean += e / static_cast<double>(errors.size());
  }
  double variance = 0.0;
  for (double e : errors) {
    variance += (e - mean) * (e - mean) / static_cast<double>(errors.size());
  }
  const std::string summary = text_of(h.output_dir() + "/summary.json");
  EXPECT_EQ(stage_value(summary, "pf", "epochs"), 23.0) << summary;
  EXPECT_EQ(stage_value(summary, "pf", "invalid_epochs"), 0.0) << summary;
  EXPECT_NEAR(stage_value(summary, "pf", "position_error_m_mean"), mean, 1e-9) << "29/23: " << summary;
  EXPECT_NEAR(stage_value(summary, "pf", "position_error_m_std"), std::sqrt(variance), 1e-9) << "population std";
  EXPECT_NEAR(stage_value(summary, "pf", "heading_error_deg_mean"), 0.1 * 180.0 / kPi, 1e-9);
  EXPECT_NEAR(stage_value(summary, "pf", "heading_error_deg_std"), 0.0, 1e-9);
  EXPECT_EQ(stage_value(summary, "uwb", "epochs"), 12.0) << "steps 5, 7, 9 of 4 pairs: " << summary;
  EXPECT_EQ(stage_value(summary, "uwb", "invalid_epochs"), 12.0) << "steps 6, 8, 10 of 4 pairs: " << summary;
  EXPECT_NEAR(stage_value(summary, "uwb", "position_error_m_mean"), 0.0, 1e-9);
  // Issue 27: the range noise the estimator reported, per stage: mean over the pairs' last values, largest.
  EXPECT_NEAR(stage_value(summary, "pf", "range_noise_std_m"), (0.25 + 0.375 + 0.125 + 0.375) / 4.0, 1e-12) << summary;
  EXPECT_NEAR(stage_value(summary, "pf", "range_noise_std_max_m"), 0.375, 1e-12) << summary;
  EXPECT_TRUE(std::isnan(stage_value(summary, "uwb", "range_noise_std_m"))) << "reported 0: none estimated: " << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("samples": \{\s*"estimate/relative_pose": 43,\s*)"
                                                    R"("plant/state": 33,\s*"estimate/relative_pose_uwb": 44\s*\})")))
      << "plant/state of all three robots (the peers' truth): " << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("rejected_samples": \{\s*"estimate/relative_pose": 1,)")))
      << summary;

  const std::vector<std::string> csv = lines_of(h.output_dir() + "/estimate_relative_pose.csv");
  ASSERT_EQ(csv.size(), 1u + 43u) << "11 steps x 4 pairs - the NaN sample";
  EXPECT_EQ(csv[0].rfind("t_s,robot_id,peer_id,header.step,header.next_step,header.stamp_ns,x,y,theta,cov[0],", 0), 0u)
      << csv[0];
  EXPECT_NE(csv[0].find(",cov[8],valid,range_noise_std_m,true_x,true_y,true_theta"), std::string::npos) << csv[0];
  // Step 0 in key order (1,2), (1,3), (2,1), (2,3); j in i's frame: robot 2 at 2 m ahead of robot 1,
  // turned +90 deg; robot 1 seen from robot 2 (facing +y, 2 m to its right) at (0, 2), -90 deg.
  EXPECT_EQ(csv[1].rfind("0.000000000,1,2,0,1,0,102.5,0,1.6707963267948966,", 0), 0u) << csv[1];
  EXPECT_NE(csv[1].find(",1,0.25,2,0,1.5707963267948966"), std::string::npos) << "valid, range noise, then the truth: " << csv[1];
  EXPECT_EQ(csv[3].rfind("0.000000000,2,1,", 0), 0u) << csv[3];
  const std::string robot1_from_2 = csv[3].substr(csv[3].rfind(",1,0.125,") + 9);
  EXPECT_NEAR(std::stod(robot1_from_2.substr(0, robot1_from_2.find(','))), 0.0, 1e-12) << csv[3];
  EXPECT_NE(csv[3].find(",-1.5707963267948966"), std::string::npos) << csv[3];
  EXPECT_EQ(lines_of(h.output_dir() + "/plant_state.csv").size(), 1u + 33u);
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("status": "completed",\s*"mission": "complete",)"))) << summary;
}

// Issue 27: paper 3's mission is its relative pose (the pf stage): never valid is an incomplete
// mission, whatever the comparison stages (uwb) did.
TEST(EvaluatorNode, ARelativePoseNeverValidIsAnIncompleteMission) {
  NodeHarness h(kRelativeScenario);
  add_evaluator(h);
  feed_relative(h, false);
  h.run({"evaluator"});
  const std::string summary = text_of(h.output_dir() + "/summary.json");
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("mission": "incomplete: relative pose estimate never valid",)")))
      << summary;
}

TEST(EvaluatorNode, ARelativeTopicInAOneRobotScenarioIsAConfigError) {
  NodeHarness h(R"(name: evaluator_one_robot
step_s: 0.1
duration_s: 1.0
seed: 1
robots:
  - {id: 1}
components:
  - {name: evaluator, type: evaluator, params: {topics: [plant/state, estimate/relative_pose_window]}}
)");
  add_evaluator(h);
  const std::string error = h.run_error<ConfigError>({"evaluator"});
  EXPECT_NE(error.find("topics: 'estimate/relative_pose_window' is a relative pose topic (key robot_id, peer_id), but "
                       "scenario 'evaluator_one_robot' has a single robot"),
            std::string::npos)
      << "expected a ConfigError, got: " << error;
}

TEST(EvaluatorNode, ARelativeTopicWithoutPlantStateIsAConfigError) {
  std::string scenario = kRelativeScenario;
  scenario.replace(scenario.find(" plant/state,"), std::string(" plant/state,").size(), "");
  NodeHarness h(scenario);
  add_evaluator(h);
  const std::string error = h.run_error<ConfigError>({"evaluator"});
  EXPECT_NE(error.find("topics: 'estimate/relative_pose' needs plant/state in topics too"), std::string::npos)
      << "expected a ConfigError, got: " << error;
}

}  // namespace
}  // namespace robodds::evaluator
