// The way-point module (paper 1) in the evaluator on the in-memory bus.
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

// Each robot's metrics from its own samples, however the evaluator finds a robot's figures
// (module/per_robot.hpp); robot 3's samples come first.
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

// Issue 27: summary.json's "mission" says whether the robot reached every way-point, and names
// an estimate that was never valid, or not valid since some time. `reached`: way-points reached by
// the last status (of 2); `valid_until_step`: the estimate is valid before this step (0: never).
std::string waypoint_run_summary(std::uint32_t reached, bool valid, std::uint64_t valid_until_step = kNeverAgain) {
  NodeHarness h(R"(name: evaluator_waypoints
step_s: 0.01
duration_s: 0.1
seed: 1
robots:
  - {id: 1}
components:
  - {name: evaluator, type: evaluator, params: {topics: [plant/state, estimate/pose, control/status, mission/waypoints],
     metrics_after_s: 0.0}}
)");
  add_evaluator(h);
  h.feed([&h, reached, valid, valid_until_step](std::uint64_t step) {
    if (step == 0) {
      idl::WaypointMission mission;
      mission.robot_id(1);
      mission.waypoints({idl::Waypoint(), idl::Waypoint()});
      h.publish("mission/waypoints", mission, step, kNeverAgain);
    }
    idl::RobotState s;
    s.robot_id(1);
    h.publish("plant/state", s, step, step + 1);
    idl::PoseEstimate e;
    e.robot_id(1);
    e.valid(valid && step < valid_until_step);
    h.publish("estimate/pose", e, step, step + 1);
    idl::ControllerStatus c;
    c.robot_id(1);
    c.waypoints_total(2);
    c.waypoints_reached(step >= 5 ? reached : 0);
    c.done(step >= 5 && reached == 2);
    h.publish("control/status", c, step, step + 1);
  });
  h.run({"evaluator"});
  return text_of(h.output_dir() + "/summary.json");
}

TEST(EvaluatorNode, TheMissionIsCompleteWhenEveryWaypointWasReached) {
  const std::string summary = waypoint_run_summary(2, true);
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("status": "completed",\s*"mission": "complete",)"))) << summary;
}

TEST(EvaluatorNode, AMissionShortOfItsWaypointsSaysHowManyAndANeverValidEstimate) {
  const std::string summary = waypoint_run_summary(1, false);
  EXPECT_TRUE(std::regex_search(summary, std::regex(R"("mission": "incomplete: 1 of 2 way-points reached; estimate never valid",)")))
      << summary;
  EXPECT_TRUE(std::regex_search(waypoint_run_summary(1, true), std::regex(R"("mission": "incomplete: 1 of 2 way-points reached",)")));
}

// Issue 27: a robot that stopped because its estimate turned invalid after it was valid says so,
// with the time from which it stayed invalid; a complete mission says nothing of it.
TEST(EvaluatorNode, AMissionShortOfItsWaypointsSaysSinceWhenTheEstimateWasNotValid) {
  const std::string summary = waypoint_run_summary(1, true, 7);
  EXPECT_TRUE(std::regex_search(
      summary, std::regex(R"("mission": "incomplete: 1 of 2 way-points reached; estimate not valid from 0.07 s to the end",)")))
      << summary;
  EXPECT_TRUE(std::regex_search(waypoint_run_summary(2, true, 7), std::regex(R"("mission": "complete",)")));
}

TEST(EvaluatorNode, WithoutAWaypointMissionThereIsNoMissionVerdict) {
  NodeHarness h(R"(name: evaluator_no_mission
step_s: 0.01
duration_s: 0.05
seed: 1
robots:
  - {id: 1}
components:
  - {name: evaluator, type: evaluator, params: {topics: [plant/state], metrics_after_s: 0.0}}
)");
  add_evaluator(h);
  h.feed([&h](std::uint64_t step) {
    idl::RobotState s;
    s.robot_id(1);
    h.publish("plant/state", s, step, step + 1);
  });
  h.run({"evaluator"});
  const std::string summary = text_of(h.output_dir() + "/summary.json");
  EXPECT_EQ(summary.find("\"mission\""), std::string::npos) << summary;
}

}  // namespace
}  // namespace robodds::evaluator
