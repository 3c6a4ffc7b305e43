// The motion module (issue 12) in the evaluator on the in-memory bus.
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

}  // namespace
}  // namespace robodds::evaluator
