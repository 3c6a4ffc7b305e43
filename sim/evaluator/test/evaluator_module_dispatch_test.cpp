// A new paper adds a metrics module without touching the core: a module registered here, in the
// test, gets the samples of the topics it attaches to, a step() per step and one finish(), and
// writes its keys into summary.json's "metrics"; the shipped modules, not registered, write none.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "robodds/idl/robodds.h"
#include "runtime/component/registry.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/testing/node_harness.hpp"
#include "sim/evaluator/module/metrics_module_registry.hpp"
#include "sim/evaluator/node/evaluator_node.hpp"
#include "sim/evaluator/node/evaluator_params.hpp"
#include "sim/evaluator/test/evaluator_test_support.hpp"

namespace robodds::evaluator {
namespace {

/// Counts each robot's plant/state samples, the steps, and how the run ended.
class SampleCounterModule : public MetricsModule {
 public:
  void configure(MetricsSetup& setup) override {
    setup.on<idl::RobotState>("plant/state", [this](const idl::RobotState& m) { ++samples_[m.robot_id()]; });
  }
  void step() override { ++steps_; }
  void finish(bool completed) override { ending_ += completed ? "completed" : "failed"; }
  void write_robot(JsonWriter& json, std::uint32_t robot) const override {
    const auto it = samples_.find(robot);
    json.value("counted_samples", static_cast<std::int64_t>(it != samples_.end() ? it->second : 0));
  }
  void write_metrics(JsonWriter& json) const override {
    json.value("counted_steps", static_cast<std::int64_t>(steps_));
    json.value("counted_ending", ending_);
  }

 private:
  std::map<std::uint32_t, std::uint64_t> samples_;  // robot -> plant/state samples
  std::uint64_t steps_ = 0;
  std::string ending_;
};

std::unique_ptr<MetricsModule> make_sample_counter_module() { return std::make_unique<SampleCounterModule>(); }

}  // namespace
}  // namespace robodds::evaluator

// Registered by hand, not by robodds_metrics_module(), which would name the module's folder.
#define ROBODDS_METRICS_MODULE_FOLDER "sim/evaluator/test"
ROBODDS_REGISTER_METRICS_MODULE(sample_counter, "test: counts samples and steps", 50,
                                robodds::evaluator::make_sample_counter_module, robodds::evaluator::Headline{});

namespace robodds::evaluator {
namespace {

using robodds::testing::NodeHarness;

/// The evaluator component with the test's module only.
void add_evaluator_with_the_counter_only(NodeHarness& h) {
  h.registry().add({"evaluator", "the evaluator with the test's module only", "sim/evaluator/config/evaluator.params.yaml",
                    [] {
                      MetricsModuleRegistry modules;
                      robodds::metrics_module_registration::register_sample_counter(modules);
                      return make_evaluator_node_with_modules(std::move(modules));
                    },
                    [] { return evaluator_param_table().doc(); },
                    [](ParamReader& reader) { (void)read_params(reader, evaluator_param_table()); }});
}

TEST(MetricsModuleDispatch, TheCoreFeedsStepsFinishesAndWritesARegisteredModule) {
  NodeHarness h(testing::kTwoRobotScenario);
  add_evaluator_with_the_counter_only(h);
  h.feed([&h](std::uint64_t step) {
    for (std::uint32_t robot : {1u, 2u}) {
      idl::RobotState s;
      s.robot_id(robot);
      // Robot 2's samples after step 3 are rejected (non-finite): no callback.
      s.x(robot == 2 && step > 3 ? std::numeric_limits<double>::quiet_NaN() : 0.0);
      h.publish("plant/state", s, step, step + 1);
    }
  });
  h.run({"evaluator"});

  const std::string summary = testing::text_of(h.output_dir() + "/summary.json");
  EXPECT_NE(summary.find(R"("1": {
        "counted_samples": 11
      })"), std::string::npos) << summary;
  EXPECT_NE(summary.find(R"("2": {
        "counted_samples": 4
      })"), std::string::npos) << summary;
  EXPECT_NE(summary.find(R"("counted_steps": 12,
    "counted_ending": "completed",
    "samples": {)"), std::string::npos) << "11 steps and the final one of on_finish(), then the core's keys: " << summary;
  EXPECT_EQ(summary.find("path_length_m"), std::string::npos) << "the shipped modules are not registered: " << summary;
  EXPECT_EQ(testing::lines_of(h.output_dir() + "/plant_state.csv").size(), 1u + 15u) << "the core still records";
}

}  // namespace
}  // namespace robodds::evaluator
