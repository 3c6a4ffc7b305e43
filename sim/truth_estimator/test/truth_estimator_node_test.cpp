// The truth estimator node on the in-memory bus: plant/state in, the same pose as a valid
// estimate/pose out.
#include "sim/truth_estimator/node/truth_estimator_node.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "robodds/idl/robodds.h"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_test_scenario.hpp"

ROBODDS_DECLARE_COMPONENT(truth_estimator);

namespace robodds::truth_estimator {
namespace {

using robodds::testing::of_instance;
using robodds::testing::ScenarioText;
using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_truth_estimator>;

const std::string kScenario = ScenarioText("truth_estimator_node", 0.01, 0.05)
                                  .robots({1, 2})
                                  .component("{name: truth, type: truth_estimator, params: {inject_nan_at_step: 3}}");

TEST(TruthEstimatorNode, PublishesTheTruePoseOfTheSameStepPerRobot) {
  Harness h(kScenario);
  h.feed([&h](std::uint64_t step) {
    for (std::uint32_t robot : {1u, 2u}) {
      idl::RobotState s;
      s.robot_id(robot);
      s.x(static_cast<double>(step));
      s.y(static_cast<double>(robot));
      s.theta(0.1 * static_cast<double>(step));
      h.publish("plant/state", s, step, step + 1);
    }
  });
  const auto& estimates = h.record<idl::PoseEstimate>("estimate/pose");
  h.run({"truth"});
  for (std::uint32_t robot : {1u, 2u}) {
    const auto mine = of_instance(estimates, robot);
    ASSERT_EQ(mine.size(), 6u);
    for (std::uint64_t step = 0; step <= 5; ++step) {
      const idl::PoseEstimate& e = mine[step];
      EXPECT_EQ(e.header().step(), step);
      EXPECT_TRUE(e.valid());
      if (step == 3) {
        EXPECT_TRUE(std::isnan(e.x())) << "inject_nan_at_step";
      } else {
        EXPECT_DOUBLE_EQ(e.x(), static_cast<double>(step));
      }
      EXPECT_DOUBLE_EQ(e.y(), static_cast<double>(robot));
      EXPECT_DOUBLE_EQ(e.theta(), 0.1 * static_cast<double>(step));
      EXPECT_DOUBLE_EQ(e.cov()[0], 0.0);
    }
  }
}

}  // namespace
}  // namespace robodds::truth_estimator
