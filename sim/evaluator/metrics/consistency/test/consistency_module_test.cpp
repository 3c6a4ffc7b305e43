// The consistency module (issue 27) in the evaluator on the in-memory bus.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <string>

#include "robodds/idl/robodds.h"
#include "runtime/testing/node_harness.hpp"
#include "sim/evaluator/test/evaluator_test_support.hpp"

namespace robodds::evaluator {
namespace {

using robodds::testing::NodeHarness;
using namespace robodds::evaluator::testing;

// 11 steps: the estimate is 1 m east of the truth and reports sigma 0.2 m (over-confident) while
// valid from step 3 to 5, sigma 1 m (consistent) from step 6; invalid before step 3 (50 m off).
TEST(EvaluatorNode, EstimatePoseAgainstItsReportedCovariance) {
  NodeHarness h(R"(name: evaluator_consistency
step_s: 0.01
duration_s: 0.1
seed: 1
robots:
  - {id: 1}
components:
  - {name: evaluator, type: evaluator, params: {topics: [plant/state, estimate/pose], metrics_after_s: 0.05}}
)");
  add_evaluator(h);
  h.feed([&h](std::uint64_t step) {
    idl::RobotState s;
    s.robot_id(1);
    s.x(10.0);
    h.publish("plant/state", s, step, step + 1);
    idl::PoseEstimate e;
    e.robot_id(1);
    e.valid(step >= 3);
    e.x(step < 3 ? 60.0 : 11.0);
    const double var = step < 6 ? 0.04 : 1.0;
    e.cov({var, 0, 0, 0, var, 0, 0, 0, 0.01});
    e.fix_noise_std_m(step < 10 ? 2.0 : 1.5);  // m: the last one is what summary.json reports
    h.publish("estimate/pose", e, step, step + 1);
  });
  h.run({"evaluator"});
  const nlohmann::json summary = nlohmann::json::parse(text_of(h.output_dir() + "/summary.json"));
  const nlohmann::json& pose = summary.at("metrics").at("estimate_pose");
  EXPECT_EQ(pose.at("samples").get<int>(), 11) << pose.dump();
  EXPECT_EQ(pose.at("valid_samples").get<int>(), 8) << "from step 0: metrics_after_s does not apply";
  EXPECT_NEAR(pose.at("overconfident_fraction").get<double>(), 3.0 / 8.0, 1e-12);
  EXPECT_NEAR(pose.at("worst_position_error_valid_m").get<double>(), 1.0, 1e-12) << "not the invalid 50 m";
  EXPECT_NEAR(pose.at("longest_overconfident_s").get<double>(), 0.03, 1e-12);
  EXPECT_EQ(pose.at("fix_noise_std_m").get<double>(), 1.5) << "issue 27: the estimated fix noise, last sample";
  EXPECT_EQ(pose.at("fix_noise_std_max_m").get<double>(), 1.5);
  EXPECT_EQ(summary.at("metrics").at("robots").at("1").at("estimate_pose"), pose) << "one robot: pooled = its own";
}

}  // namespace
}  // namespace robodds::evaluator
