// The evaluator node on the in-memory bus: records the listed topics into CSV files and writes
// summary.json ("status": "completed") when the run finishes, or what it has with "status":
// "failed" and the reason when the run fails; non-finite samples are dropped and counted.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <fstream>
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

TEST(EvaluatorNode, WritesEveryValidSampleToCsvAndCountsTheRejectedOne) {
  NodeHarness h(kTwoRobotScenario);
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
  // What the plots (sim/report/report.py) take for their subtitle and for the start of their RMSEs.
  EXPECT_NE(summary.find("\"scenario\": \"evaluator_node\",\n  \"description\": \"two robots, \\\"quoted\\\"\",\n"),
            std::string::npos) << summary;
  EXPECT_NE(summary.find("\"metrics_after_s\": 0,"), std::string::npos) << summary;
}

TEST(EvaluatorNode, AFailedRunKeepsTheRowsSoFarAndSaysWhyInTheSummary) {
  NodeHarness h(kTwoRobotScenario);
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

// Real time, stopped by the first signal (HostOptions::graceful_stop) from step 4 of 0..10 (or the
// first step after it the loop ran, on a busy machine): the run ends cleanly after that step,
// summary.json says "completed", who stopped it and when, with the metrics and rows of the steps
// that ran.
TEST(EvaluatorNode, ARealTimeRunStoppedBySignalIsCompletedWithTheStopAndTheMetricsSoFar) {
  NodeHarness h(kTwoRobotScenario);
  add_evaluator(h);
  h.set_mode(TimeMode::kRealtime);
  std::atomic<bool> graceful{false};
  std::uint64_t stop_step = 0;
  h.options().graceful_stop = &graceful;
  h.feed([&](std::uint64_t step) {
    for (std::uint32_t robot : {1u, 2u}) {
      idl::RobotState s;
      s.robot_id(robot);
      s.x(static_cast<double>(step));
      h.publish("plant/state", s, step, step + 1);
    }
    if (step >= 4 && !graceful) {
      graceful = true;
      stop_step = step;
    }
  });
  const RunStats stats = h.run({"evaluator"});
  ASSERT_TRUE(graceful) << "the loop skipped every step from 4 on";
  EXPECT_EQ(stats.stopped_by, "signal");
  const std::string summary = text_of(h.output_dir() + "/summary.json");
  EXPECT_EQ(summary.rfind("{\n  \"status\": \"completed\",\n  \"stopped_by\": \"signal\",\n  \"stopped_at_s\": ", 0), 0u) << summary;
  EXPECT_NEAR(summary_value(summary, "stopped_at_s"), 0.01 * static_cast<double>(stop_step), 1e-9) << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("stopped_at_utc": "20\d\d-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z")"))) << summary;
  EXPECT_NE(summary.find("\"steps\": " + std::to_string(stop_step + 1) + ","), std::string::npos) << summary;
  EXPECT_TRUE(std::regex_search(summary, std::regex("\"1\": \\{\\s*\"path_length_m\": " + std::to_string(stop_step) + ",")))
      << "metrics of the steps run: " << summary;
}

/// The number after "<key>": in summary.json (the first occurrence); NaN if absent.
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

TEST(EvaluatorNode, AnUnknownTopicNamesTheClosest) {
  NodeHarness h(R"(name: evaluator_node
step_s: 0.01
duration_s: 0.1
seed: 1
robots:
  - {id: 1}
components:
  - {name: evaluator, type: evaluator, params: {topics: [plant/stat]}}
)");
  add_evaluator(h);
  const std::string error = h.run_error<ConfigError>({"evaluator"});
  EXPECT_NE(error.find("topics: unknown topic 'plant/stat'; did you mean 'plant/state'?"), std::string::npos) << error;
}

// Real time: the files are opened in on_start(), before the clock starts (opening them at step 0
// made steps 0-1 late at 200 robots); lockstep: at the first step, so a run stopped at its start
// barrier leaves no files. The feeder runs before the evaluator at each step: what it sees at step
// 0 is what on_start() did.
TEST(EvaluatorNode, OpensItsFilesBeforeTheClockInRealTimeAndAtTheFirstStepInLockstep) {
  for (const TimeMode mode : {TimeMode::kRealtime, TimeMode::kLockstep}) {
    NodeHarness h(kTwoRobotScenario);
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
