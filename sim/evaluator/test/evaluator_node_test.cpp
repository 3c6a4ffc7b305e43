// The evaluator node on the in-memory bus: records the listed topics into CSV files and writes
// summary.json ("status": "completed") when the run finishes, or what it has with "status":
// "failed" and the reason when the run fails; non-finite samples are dropped and counted.
#include "sim/evaluator/node/evaluator_node.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "robodds/idl/robodds.h"
#include "runtime/error.hpp"
#include "runtime/registry.hpp"
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
robots:
  - {id: 1}
  - {id: 2}
components:
  - {name: observer, type: range_rate_observer, params: {sta: {b: 3.5}}}
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

}  // namespace
}  // namespace robodds::evaluator
