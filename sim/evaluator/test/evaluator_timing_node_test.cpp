// Compute times end to end, co-located: what a component records in its
// ComponentContext::compute_times() reaches summary.json's run.timing through the host
// (RunFigures::hosts) and the evaluator. (A file apart from evaluator_node_test.cpp: the run
// section is written by other code than the metrics that test covers.)
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "robodds/idl/robodds.h"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_harness.hpp"

ROBODDS_DECLARE_COMPONENT(evaluator);

namespace robodds::evaluator {
namespace {

using robodds::testing::NodeHarness;

const char* kScenario = R"(name: evaluator_timing
step_s: 0.01
duration_s: 0.1
seed: 1
robots:
  - {id: 1}
components:
  - {name: worker, type: test_worker}
  - {name: evaluator, type: evaluator, params: {topics: [plant/state], metrics_after_s: 0.0}}
)";

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(EvaluatorTimingNode, AComponentsComputeTimesReachRunTimingOfTheSummary) {
  NodeHarness h(kScenario);
  robodds::component_registration::register_evaluator(h.registry());
  ComputeTimes* times = nullptr;
  // Steps 0..10 record 1..11 ms: median 6, p99 (nearest rank, the 11th of 11) 11, max 11.
  h.add_script(
      "test_worker", [&times](ComponentContext& ctx) { times = &ctx.compute_times(); },
      [&times](const StepInfo& info) {
        times->add_ms("cycle", static_cast<double>(info.step + 1));
        times->add_ms("window", 0.002 * static_cast<double>(info.step + 1));
      });
  h.feed([&h](std::uint64_t step) {
    idl::RobotState s;
    s.robot_id(1);
    h.publish("plant/state", s, step, step + 1);
  });
  h.set_deploy_label("colocated");
  h.run({"worker", "evaluator"});

  const std::string summary = text_of(h.output_dir() + "/summary.json");
  std::smatch run;
  ASSERT_TRUE(std::regex_search(summary, run, std::regex("\"run\": \\{[\\s\\S]*?\n  \\}"))) << summary;
  const std::string expected =
      "    \"timing\": {\n"
      "      \"cycle\": {\n        \"cycle_ms_median\": 6,\n        \"cycle_ms_p99\": 11,\n"
      "        \"cycle_ms_max\": 11,\n        \"cycles\": 11,\n        \"component\": \"worker\",\n"
      "        \"components\": 1\n      },\n"
      "      \"window\": {\n        \"cycle_ms_median\": 0.012,\n        \"cycle_ms_p99\": 0.022,\n"
      "        \"cycle_ms_max\": 0.022,\n        \"cycles\": 11,\n        \"component\": \"worker\",\n"
      "        \"components\": 1\n      }\n"
      "    }\n";
  EXPECT_NE(run.str().find(expected), std::string::npos) << run.str();
}

}  // namespace
}  // namespace robodds::evaluator
