// The evaluator node on the in-memory bus: records the listed topics into CSV files and writes
// summary.json ("status": "completed") when the run finishes, or what it has with "status":
// "failed" and the reason when the run fails; non-finite samples are dropped and counted.
#include "sim/evaluator/node/evaluator_node.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "common/angle.hpp"
#include "common/model/pose2.hpp"
#include "robodds/idl/robodds.h"
#include "runtime/base/error.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_harness.hpp"

ROBODDS_DECLARE_COMPONENT(evaluator);

namespace robodds::evaluator {
namespace {

using robodds::testing::NodeHarness;

const char* kScenario = R"(name: evaluator_node
step_s: 0.01
duration_s: 0.1
seed: 1
robots:
  - {id: 1}
  - {id: 2}
components:
  - {name: evaluator, type: evaluator, params: {topics: [plant/state], metrics_after_s: 0.0}}
)";

void add_evaluator(NodeHarness& h) {
  robodds::component_registration::register_evaluator(h.registry());
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
  }
  return lines;
}

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(EvaluatorNode, WritesEveryValidSampleToCsvAndCountsTheRejectedOne) {
  NodeHarness h(kScenario);
  add_evaluator(h);
  h.feed([&h](std::uint64_t step) {
    for (std::uint32_t robot : {1u, 2u}) {
      idl::RobotState s;
      s.robot_id(robot);
      s.x(step == 3 && robot == 1 ? std::numeric_limits<double>::quiet_NaN() : static_cast<double>(step));
      s.y(static_cast<double>(robot));
      h.publish("plant/state", s, step, step + 1);
    }
  });
  h.run({"evaluator"});

  const std::vector<std::string> csv = lines_of(h.output_dir() + "/plant_state.csv");
  ASSERT_EQ(csv.size(), 1u + 22u - 1u) << "header + 2 robots x 11 steps - the NaN sample";
  EXPECT_EQ(csv[0], "t_s,robot_id,header.step,header.next_step,header.stamp_ns,x,y,theta,v,omega");
  // Robot by robot within a step (key order), steps in order; stamps as seconds.
  EXPECT_EQ(csv[1], "0.000000000,1,0,1,0,0,1,0,0,0");
  EXPECT_EQ(csv[2], "0.000000000,2,0,1,0,0,2,0,0,0");
  EXPECT_EQ(csv[7], "0.030000000,2,3,4,30000000,3,2,0,0,0") << "robot 1's NaN sample of step 3 is missing";

  const std::string summary = text_of(h.output_dir() + "/summary.json");
  EXPECT_NE(summary.find("\"steps\": 11"), std::string::npos) << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("rejected_samples": \{\s*"plant/state": 1\s*\})"))) << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("samples": \{\s*"plant/state": 21\s*\})"))) << summary;
  EXPECT_EQ(summary.rfind("{\n  \"status\": \"completed\",\n", 0), 0u) << summary;
  EXPECT_EQ(summary.find("\"reason\""), std::string::npos) << summary;
}

// Each robot's metrics from its own samples, however the evaluator finds a robot's figures
// (sample_metrics.hpp: Metrics::robot()); robot 3's samples come first.
TEST(EvaluatorNode, EachRobotsMetricsComeFromItsOwnSamples) {
  NodeHarness h(R"(name: evaluator_robots
step_s: 0.01
duration_s: 0.1
seed: 1
robots:
  - {id: 3}
  - {id: 1}
  - {id: 2}
components:
  - {name: evaluator, type: evaluator, params: {topics: [plant/state], metrics_after_s: 0.0}}
)");
  add_evaluator(h);
  h.feed([&h](std::uint64_t step) {
    for (std::uint32_t robot : {3u, 1u, 2u}) {
      idl::RobotState s;
      s.robot_id(robot);
      s.x(static_cast<double>(step) * robot);
      s.y(10.0 * robot);
      h.publish("plant/state", s, step, step + 1);
    }
  });
  h.run({"evaluator"});
  const std::string summary = text_of(h.output_dir() + "/summary.json");
  for (std::uint32_t robot : {1u, 2u, 3u}) {
    std::smatch m;
    const std::regex pattern("\"" + std::to_string(robot) + "\": \\{\\s*\"path_length_m\": ([0-9.eE+-]+),\\s*"
                             "\"final_x_m\": ([0-9.eE+-]+),\\s*\"final_y_m\": ([0-9.eE+-]+)");
    ASSERT_TRUE(std::regex_search(summary, m, pattern)) << "robot " << robot << ": " << summary;
    EXPECT_NEAR(std::stod(m[1].str()), 10.0 * robot, 1e-9) << "robot " << robot;
    EXPECT_NEAR(std::stod(m[2].str()), 10.0 * robot, 1e-9) << "robot " << robot;
    EXPECT_NEAR(std::stod(m[3].str()), 10.0 * robot, 1e-9) << "robot " << robot;
  }
}

TEST(EvaluatorNode, AFailedRunKeepsTheRowsSoFarAndSaysWhyInTheSummary) {
  NodeHarness h(kScenario);
  add_evaluator(h);
  h.feed([&h](std::uint64_t step) {
    if (step == 6) {
      throw RunError("lockstep: component 'plant' waited 2 s for its inputs");
    }
    for (std::uint32_t robot : {1u, 2u}) {
      idl::RobotState s;
      s.robot_id(robot);
      s.x(static_cast<double>(step));
      h.publish("plant/state", s, step, step + 1);
    }
  });
  EXPECT_THROW(h.run({"evaluator"}), RunError);

  const std::vector<std::string> csv = lines_of(h.output_dir() + "/plant_state.csv");
  EXPECT_EQ(csv.size(), 1u + 2u * 6u) << "header + 2 robots x steps 0..5, on disk although the run failed";
  const std::string summary = text_of(h.output_dir() + "/summary.json");
  EXPECT_EQ(summary.rfind("{\n  \"status\": \"failed\",\n  \"reason\": \"component 'feeder' failed at step 6: lockstep: "
                          "component 'plant' waited 2 s for its inputs\",\n", 0),
            0u) << "the host's error line: " << summary;
  EXPECT_NE(summary.find("\"steps\": 6"), std::string::npos) << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("samples": \{\s*"plant/state": 12\s*\})"))) << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("1": \{\s*"path_length_m": 5,)"))) << "metrics of the data so far: " << summary;
}

/// The number after "<key>": in summary.json (the first occurrence); NaN if absent.
double summary_value(const std::string& summary, const std::string& key) {
  std::smatch m;
  const std::regex pattern("\"" + key + "\": ?(-?[0-9.eE+-]+)");
  return std::regex_search(summary, m, pattern) ? std::stod(m[1].str()) : std::numeric_limits<double>::quiet_NaN();
}

// Issue 12: the extremes of what the plant applied (plant/state) and of what the controller
// commanded (plant/cmd) apart, wheel speeds with the robot body's wheel_base_m (0.3 m here), and the
// time of the first valid estimate.
TEST(EvaluatorNode, AppliedAndCommandedExtremesApartAndTheTimeToValid) {
  NodeHarness h(R"(name: evaluator_motion
step_s: 0.01
duration_s: 0.1
seed: 1
facts:
  robot_body: {wheel_base_m: 0.3}
robots:
  - {id: 1}
components:
  - {name: plant, type: plant}
  - {name: evaluator, type: evaluator, params: {topics: [plant/state, plant/cmd, estimate/pose], metrics_after_s: 0.0}}
)");
  add_evaluator(h);
  h.feed([&h](std::uint64_t step) {
    idl::VelocityCommand cmd;
    cmd.robot_id(1);
    cmd.mode(idl::VELOCITY);
    cmd.v(step == 5 ? 18.0 : 1.0);  // one 18 m/s command the plant never applies
    cmd.omega(step == 5 ? -60.0 : 0.0);
    h.publish("plant/cmd", cmd, step, step + 1);
    idl::RobotState s;
    s.robot_id(1);
    s.v(0.01 * static_cast<double>(step));  // 1 m/s^2
    s.omega(step == 6 ? 0.5 : 0.0);         // 50 rad/s^2 up and down
    h.publish("plant/state", s, step, step + 1);
    idl::PoseEstimate e;
    e.robot_id(1);
    e.valid(step >= 4);
    h.publish("estimate/pose", e, step, step + 1);
  });
  h.run({"evaluator"});
  const std::string summary = text_of(h.output_dir() + "/summary.json");
  EXPECT_NEAR(summary_value(summary, "max_abs_v_applied_mps"), 0.1, 1e-12) << summary;
  EXPECT_NEAR(summary_value(summary, "max_abs_omega_applied_radps"), 0.5, 1e-12);
  EXPECT_NEAR(summary_value(summary, "max_abs_wheel_speed_applied_mps"), 0.06 + 0.15 * 0.5, 1e-12) << "step 6, D = 0.3 m";
  EXPECT_NEAR(summary_value(summary, "max_abs_accel_applied_mps2"), 1.0, 1e-9);
  EXPECT_NEAR(summary_value(summary, "max_abs_angular_accel_applied_radps2"), 50.0, 1e-9);
  EXPECT_NEAR(summary_value(summary, "max_abs_v_commanded_mps"), 18.0, 1e-12);
  EXPECT_NEAR(summary_value(summary, "max_abs_omega_commanded_radps"), 60.0, 1e-12);
  EXPECT_NEAR(summary_value(summary, "max_abs_wheel_speed_commanded_mps"), 18.0 + 0.15 * 60.0, 1e-12);
  EXPECT_NEAR(summary_value(summary, "max_abs_accel_commanded_mps2"), 1700.0, 1e-6);
  EXPECT_NEAR(summary_value(summary, "time_to_valid_s"), 0.04, 1e-12);
}

// A scenario with a hot standby (standby_for): summary.json "standby" holds each robot's longest
// gap between estimate/pose samples (the hand-over time); without one there is no such section.
const char* kStandbyScenario = R"(name: evaluator_standby
step_s: 0.01
duration_s: 0.1
seed: 1
robots:
  - {id: 1}
components:
  - {name: estimator, type: pf_estimator}
  - {name: estimator_standby, type: pf_estimator, standby_for: estimator}
  - {name: evaluator, type: evaluator, params: {topics: [estimate/pose], metrics_after_s: 0.0}}
)";

void feed_estimates_with_a_gap(NodeHarness& h) {
  h.feed([&h](std::uint64_t step) {
    if (step >= 3 && step <= 6) {
      return;  // the primary died after step 2, the standby's first sample is step 7
    }
    idl::PoseEstimate s;
    s.robot_id(1);
    h.publish("estimate/pose", s, step, step == 2 ? 7 : step + 1);  // lockstep: nothing before step 7
  });
}

TEST(EvaluatorNode, WithAHotStandbyTheSummaryHasTheHandOverTime) {
  NodeHarness h(kStandbyScenario);
  add_evaluator(h);
  feed_estimates_with_a_gap(h);
  h.run({"evaluator"});
  const std::string summary = text_of(h.output_dir() + "/summary.json");
  EXPECT_TRUE(std::regex_search(
      summary, std::regex(R"("standby": \{\s*"topic": "estimate/pose",\s*"robots": \{\s*"1": \{\s*"handover_s": 0.05,\s*)"
                          R"("from_s": 0.02,\s*"to_s": 0.07,\s*"samples": 7\s*\})")))
      << summary;
}

TEST(EvaluatorNode, WithoutAHotStandbyTheSummaryHasNoStandbySection) {
  std::string scenario = kStandbyScenario;
  scenario.erase(scenario.find("  - {name: estimator_standby"), std::string("  - {name: estimator_standby, type: pf_estimator, standby_for: estimator}\n").size());
  NodeHarness h(scenario);
  add_evaluator(h);
  feed_estimates_with_a_gap(h);
  h.run({"evaluator"});
  const std::string summary = text_of(h.output_dir() + "/summary.json");
  EXPECT_EQ(summary.find("\"standby\""), std::string::npos) << summary;
}

// Paper 2: the topics keyed (robot_id, target_id) are recorded per robot whatever the target
// (robot 1's streams move from target 1 to target 2 at step 6), and with plant/state and
// mission/target recorded the summary holds the paper-2 metrics. Two robots stand still 1 m
// outside their circles (radius RMSE 1 m, settled at once, opposite each other: no spacing
// error), the super-twisting estimate is 0.5 m/s off the true rate (0: they stand), the
// linear one -0.25 m/s; robot 1's super-twisting observer restarts at its target change.
const char* kPaper2Scenario = R"(name: evaluator_paper2
step_s: 0.01
duration_s: 0.1
seed: 1
facts:
  range_accel_bound_mps2: 3.5
robots:
  - {id: 1}
  - {id: 2}
components:
  - {name: observer, type: range_rate_observer, params: {sta: {b: 4.0}}}  # not what the evaluator reads
  - {name: evaluator, type: evaluator, params: {topics: [plant/state, mission/target, sensor/range, observer/range_rate,
     observer/range_rate_linear], metrics_after_s: 0.0}}
)";

void feed_paper2(NodeHarness& h) {
  h.feed([&h](std::uint64_t step) {
    for (std::uint32_t robot : {1u, 2u}) {
      const bool second = robot == 1 && step >= 6;  // robot 1 on target 2 from step 6
      const std::uint32_t target = second ? 2 : 1;
      if (step == 0 || step == 6) {
        idl::TargetAssignment a;
        a.robot_id(robot);
        a.active(true);
        a.target_id(target);
        a.target_x(second ? 11.0 : 0.0);
        a.target_y(second ? 20.0 : 0.0);
        a.desired_radius(second ? 19.0 : 10.0);
        h.publish("mission/target", a, step, step == 0 ? 6 : kNeverAgain);
      }
      idl::RobotState s;
      s.robot_id(robot);
      s.x(robot == 1 ? 11.0 : -11.0);
      h.publish("plant/state", s, step, step + 1);
      idl::RangeMeasurement r;
      r.robot_id(robot);
      r.target_id(target);
      r.range(second ? 20.0 : 11.0);
      h.publish("sensor/range", r, step, step + 1);
      for (const char* topic : {"observer/range_rate", "observer/range_rate_linear"}) {
        const bool sta = std::string(topic) == "observer/range_rate";
        idl::RangeRateEstimate e;
        e.robot_id(robot);
        e.target_id(target);
        e.range_rate(sta ? 0.5 : -0.25);
        e.valid(true);
        e.restarted(sta && robot == 1 && step == 6);
        h.publish(topic, e, step, step + 1);
      }
    }
  });
}

TEST(EvaluatorNode, RecordsTargetKeyedTopicsPerRobotAndWritesThePaper2Metrics) {
  NodeHarness h(kPaper2Scenario);
  add_evaluator(h);
  feed_paper2(h);
  h.run({"evaluator"});
  const std::vector<std::string> range = lines_of(h.output_dir() + "/sensor_range.csv");
  ASSERT_EQ(range.size(), 1u + 22u) << "2 robots x 11 steps, robot 1's across its two targets";
  EXPECT_EQ(range[0].rfind("t_s,robot_id,target_id,header.step,", 0), 0u) << range[0];
  EXPECT_EQ(range[13].rfind("0.060000000,1,2,6,", 0), 0u) << "robot 1 on target 2 from step 6: " << range[13];
  EXPECT_EQ(lines_of(h.output_dir() + "/observer_range_rate_linear.csv").size(), 1u + 22u);
  EXPECT_EQ(lines_of(h.output_dir() + "/mission_target.csv").size(), 1u + 4u);

  const std::string summary = text_of(h.output_dir() + "/summary.json");
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("phase1": \{\s*"start_s": 0,\s*"settle_time_s": 0,\s*)"
                                                    R"("radius_rmse_m": 1,\s*"spacing_rmse_deg": 0\s*\})")))
      << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("phase2": \{\s*"start_s": 0.06,\s*"settle_time_s": 0,\s*)"
                                                    R"("radius_rmse_m": 1\s*\})")))
      << "alone on each target: no gaps; " << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("observer": \{\s*"sta": \{\s*"steady_rmse_mps": 0.5,\s*)"
                                                    R"("convergence_s": -1,\s*"max_error_after_restart_mps": 0.5,\s*)"
                                                    R"("restarts": 1,\s*"matched_samples": 22\s*\},\s*)"
                                                    R"("linear": \{\s*"steady_rmse_mps": 0.25,\s*"restarts": 0,)")))
      << "no transient window in 0.1 s; " << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("range_accel_over_b_fraction": 0,\s*"range_accel_b": 3.5,)")))
      << summary;
}

TEST(EvaluatorNode, WithoutMissionTargetThereAreNoPaper2Metrics) {
  std::string scenario = kPaper2Scenario;
  scenario.replace(scenario.find("mission/target, "), std::string("mission/target, ").size(), "");
  NodeHarness h(scenario);
  add_evaluator(h);
  feed_paper2(h);
  h.run({"evaluator"});
  const std::string summary = text_of(h.output_dir() + "/summary.json");
  EXPECT_EQ(summary.find("\"phase1\""), std::string::npos) << summary;
  EXPECT_EQ(summary.find("\"observer\""), std::string::npos) << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("observer/range_rate": 22,)"))) << summary;
}

TEST(EvaluatorNode, WithoutObserverTopicsThePaper2MetricsHaveNoObserverPart) {
  std::string scenario = kPaper2Scenario;
  const std::string observers = ", observer/range_rate,\n     observer/range_rate_linear";
  ASSERT_NE(scenario.find(observers), std::string::npos);
  scenario.replace(scenario.find(observers), observers.size(), "");
  NodeHarness h(scenario);
  add_evaluator(h);
  feed_paper2(h);
  h.run({"evaluator"});
  const std::string summary = text_of(h.output_dir() + "/summary.json");
  EXPECT_NE(summary.find("\"phase1\""), std::string::npos) << summary;
  EXPECT_EQ(summary.find("\"observer\""), std::string::npos) << summary;
}

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

void feed_relative(NodeHarness& h) {
  h.feed([&h](std::uint64_t step) {
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
        e.valid(true);
        if (robot == 1 && peer == 3 && step == 6) {
          e.x(std::numeric_limits<double>::quiet_NaN());
        }
        h.publish("estimate/relative_pose", e, step, step + 1);
        e.x(truth.x);
        e.theta(truth.theta);
        e.valid(step % 2 == 1);
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
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("samples": \{\s*"estimate/relative_pose": 43,\s*)"
                                                    R"("plant/state": 33,\s*"estimate/relative_pose_uwb": 44\s*\})")))
      << "plant/state of all three robots (the peers' truth): " << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("rejected_samples": \{\s*"estimate/relative_pose": 1,)")))
      << summary;

  const std::vector<std::string> csv = lines_of(h.output_dir() + "/estimate_relative_pose.csv");
  ASSERT_EQ(csv.size(), 1u + 43u) << "11 steps x 4 pairs - the NaN sample";
  EXPECT_EQ(csv[0].rfind("t_s,robot_id,peer_id,header.step,header.next_step,header.stamp_ns,x,y,theta,cov[0],", 0), 0u)
      << csv[0];
  EXPECT_NE(csv[0].find(",cov[8],valid,true_x,true_y,true_theta"), std::string::npos) << csv[0];
  // Step 0 in key order (1,2), (1,3), (2,1), (2,3); j in i's frame: robot 2 at 2 m ahead of robot 1,
  // turned +90 deg; robot 1 seen from robot 2 (facing +y, 2 m to its right) at (0, 2), -90 deg.
  EXPECT_EQ(csv[1].rfind("0.000000000,1,2,0,1,0,102.5,0,1.6707963267948966,", 0), 0u) << csv[1];
  EXPECT_NE(csv[1].find(",1,2,0,1.5707963267948966"), std::string::npos) << "valid, then the truth: " << csv[1];
  EXPECT_EQ(csv[3].rfind("0.000000000,2,1,", 0), 0u) << csv[3];
  const std::string robot1_from_2 = csv[3].substr(csv[3].rfind(",1,") + 3);
  EXPECT_NEAR(std::stod(robot1_from_2.substr(0, robot1_from_2.find(','))), 0.0, 1e-12) << csv[3];
  EXPECT_NE(csv[3].find(",-1.5707963267948966"), std::string::npos) << csv[3];
  EXPECT_EQ(lines_of(h.output_dir() + "/plant_state.csv").size(), 1u + 33u);
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

TEST(EvaluatorNode, ATopicThatIsNotPerRobotIsAConfigError) {
  NodeHarness h(R"(name: evaluator_node
step_s: 0.01
duration_s: 0.1
seed: 1
robots:
  - {id: 1}
components:
  - {name: evaluator, type: evaluator, params: {topics: [sim/clock]}}
)");
  add_evaluator(h);
  const std::string error = h.run_error<ConfigError>({"evaluator"});
  EXPECT_NE(error.find("sim/clock"), std::string::npos) << "expected a ConfigError, got: " << error;
}

// Real time: the files are opened in on_start(), before the clock starts (opening them at step 0
// made steps 0-1 late at 200 robots); lockstep: at the first step, so a run stopped at its start
// barrier leaves no files. The feeder runs before the evaluator at each step: what it sees at step
// 0 is what on_start() did.
TEST(EvaluatorNode, OpensItsFilesBeforeTheClockInRealTimeAndAtTheFirstStepInLockstep) {
  for (const TimeMode mode : {TimeMode::kRealtime, TimeMode::kLockstep}) {
    NodeHarness h(kScenario);
    add_evaluator(h);
    h.set_mode(mode);
    std::optional<bool> file_at_step0;
    h.feed([&](std::uint64_t step) {
      if (!file_at_step0) {
        file_at_step0 = std::ifstream(h.output_dir() + "/plant_state.csv").good();
      }
      for (std::uint32_t robot : {1u, 2u}) {
        idl::RobotState state;
        state.robot_id(robot);
        h.publish("plant/state", state, step, step + 1);
      }
    });
    h.run({"evaluator"});
    ASSERT_TRUE(file_at_step0.has_value());
    EXPECT_EQ(*file_at_step0, mode == TimeMode::kRealtime) << (mode == TimeMode::kRealtime ? "real time" : "lockstep");
  }
}

}  // namespace
}  // namespace robodds::evaluator
