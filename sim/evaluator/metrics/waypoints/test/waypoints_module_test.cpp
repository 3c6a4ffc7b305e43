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

}  // namespace
}  // namespace robodds::evaluator
