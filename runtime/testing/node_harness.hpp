#pragma once
// Test fixture for node adapters and the host loop: a scenario, an in-memory bus and one Host
// that runs the chosen components in lockstep and is its own coordinator, as `robodds run`
// does co-located, but without Fast DDS. A test
// - registers the component types it runs (registry(), add_script()),
// - writes input samples with the step/next_step it chooses (publish(), usually from feed(),
//   which runs at every step before the components under test),
// - records what the components publish (record()) and runs to the end of the scenario (run()).
// Test-only: link robodds_node_harness (it needs GoogleTest for the temp files).

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "robodds/idl/robodds_visit.hpp"
#include "runtime/component/component.hpp"
#include "runtime/host/host.hpp"
#include "runtime/host/host_slot.hpp"
#include "runtime/bus/memory_bus.hpp"
#include "runtime/io/notifier.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/io/sample_checks.hpp"
#include "runtime/config/scenario.hpp"
#include "runtime/topics/topic_catalog.hpp"
#include "tests/support/temp_file.hpp"

namespace robodds::testing {

/// Defaults file of test-defined component types: none (they have no parameters).
inline constexpr const char* kNoParamsFile = "(none: a test component)";

/// The parameter table of test-defined component types: empty.
inline params::ParamDoc no_params() { return {}; }

/// A test-defined component: `configure` declares its inputs/outputs, `step` runs at each due
/// step, `finish` (optional) once after the last.
class ScriptComponent : public Component {
 public:
  ScriptComponent(std::function<void(ComponentContext&)> configure, std::function<void(const StepInfo&)> step,
                  std::function<void(const StepInfo&)> finish = nullptr)
      : configure_(std::move(configure)), step_(std::move(step)), finish_(std::move(finish)) {}
  void configure(ComponentContext& ctx) override {
    if (configure_) {
      configure_(ctx);
    }
  }
  void on_step(const StepInfo& info) override {
    if (step_) {
      step_(info);
    }
  }
  void on_finish(const StepInfo& info) override {
    if (finish_) {
      finish_(info);
    }
  }

 private:
  std::function<void(ComponentContext&)> configure_;
  std::function<void(const StepInfo&)> step_;
  std::function<void(const StepInfo&)> finish_;
};

class NodeHarness {
 public:
  /// `scenario_yaml`: the text of a scenario file (step_s, duration_s, robots, components with
  /// params). A component named "feeder" (type test_feeder) is added and listed first in run(),
  /// so its feed() runs at every step before the components under test.
  explicit NodeHarness(const std::string& scenario_yaml)
      : scenario_file_(test_support::write_test_file("scenario.yaml", scenario_yaml)),
        scenario_(load_scenario(scenario_file_)) {
    scenario_.components.push_back(ComponentSpec{"feeder", "test_feeder", {}, {}, {}});
    registry_.add({"test_feeder", "feeds test inputs", kNoParamsFile, [this] {
                     return std::make_unique<ScriptComponent>(nullptr, [this](const StepInfo& info) {
                       if (feed_) {
                         feed_(info.step);
                       }
                     });
                   }, no_params, nullptr});
    // Next to the scenario file, named after the running test case like it.
    output_dir_ = scenario_file_.substr(0, scenario_file_.size() - std::string("scenario.yaml").size()) + "out";
    std::filesystem::remove_all(output_dir_);
    options_.member = "host";
    options_.members = {"host"};
    options_.coordinator = true;
    options_.single_process = true;
    // Fail fast: a unit test that waits seconds has already failed.
    options_.input_timeout_s = 2.0;
    options_.start_timeout_s = 2.0;
    options_.tick_timeout_s = 2.0;
    // Real-time node tests judge a component, not the machine: on a loaded test machine a short
    // run may skip more than the default 5 % of its steps. The overrun rule has its own tests
    // (overrun_counter_test, integration.realtime_overrun).
    options_.max_missed_steps = std::numeric_limits<std::uint64_t>::max();
  }

  // Registered types and callbacks point at this harness: it stays where it was made.
  NodeHarness(const NodeHarness&) = delete;
  NodeHarness& operator=(const NodeHarness&) = delete;

  ComponentRegistry& registry() { return registry_; }
  Scenario& scenario() { return scenario_; }
  HostOptions& options() { return options_; }
  MemoryBus& bus() { return bus_; }
  /// Where the evaluator writes (RunContext::output_dir); removed when the harness is made.
  const std::string& output_dir() const { return output_dir_; }

  /// Registers a test-defined component type without parameters.
  void add_script(const std::string& type, std::function<void(ComponentContext&)> configure,
                  std::function<void(const StepInfo&)> step, std::function<void(const StepInfo&)> finish = nullptr) {
    registry_.add({type, "test script", kNoParamsFile, [configure, step, finish] {
                     return std::make_unique<ScriptComponent>(configure, step, finish);
                   }, no_params, nullptr});
  }

  /// The time mode of run() (default lockstep).
  void set_mode(TimeMode mode) { mode_ = mode; }
  /// RunContext::single_process of run() (default true, a co-located run; false: the components
  /// read as a host of a run across processes would, on this in-memory bus).
  void set_single_process(bool single_process) { single_process_ = single_process; }
  /// RunContext::deploy_label of run() (default empty: the evaluator writes no "run" section).
  void set_deploy_label(std::string label) { deploy_label_ = std::move(label); }

  /// RunContext::assigned_producers of run() (default none: the first writer rule).
  void assign_producers(AssignedProducers producers) {
    assigned_ = std::make_shared<const AssignedProducers>(std::move(producers));
  }
  /// RunContext::produced_instances of run() (default none).
  void produce_instances(ProducedInstances instances) {
    produced_ = std::make_shared<const ProducedInstances>(std::move(instances));
  }
  /// Runs `feed(step)` at every step, before the components under test.
  void feed(std::function<void(std::uint64_t step)> feed) { feed_ = std::move(feed); }

  /// Writes `sample` on `topic` as its producer would at `step` (stamp = step * step_s in
  /// lockstep, the wall clock in real time) with the given next_step; delivered (receive time:
  /// now) before this returns.
  template <class Msg>
  void publish(const std::string& topic, Msg sample, std::uint64_t step, std::uint64_t next_step) {
    publish_stamped(topic, std::move(sample), step, next_step,
                    mode_ == TimeMode::kRealtime ? wall_clock_now_ns() : host_detail::sim_stamp_ns(step, scenario_.step_s));
  }
  /// publish() with the header stamp the test chooses (e.g. a hostile one).
  template <class Msg>
  void publish_stamped(const std::string& topic, Msg sample, std::uint64_t step, std::uint64_t next_step, std::int64_t stamp_ns) {
    const TopicInfo& info = topic_info(topic);
    sample.header().step(step);
    sample.header().next_step(next_step);
    sample.header().stamp_ns(stamp_ns);
    bus_.writer(topic, info.type_name, qos_profile_for(info, TimeMode::kLockstep, true))->write(&sample);
  }

  /// Every sample written on `topic` from now on, in write order (call before run()).
  template <class Msg>
  const std::vector<Msg>& record(const std::string& topic) {
    const TopicInfo& info = topic_info(topic);
    auto log = std::make_shared<std::vector<Msg>>();
    records_.push_back(log);
    readers_.push_back(bus_.reader(topic, info.type_name, qos_profile_for(info, TimeMode::kLockstep, true),
                                   [log](const void* sample, const SampleMeta&) { log->push_back(*static_cast<const Msg*>(sample)); },
                                   [](const std::string&) {}));
    return *log;
  }

  /// Configures `components` (instance names of the scenario) in one host and runs steps
  /// 0..last_step(). ConfigError / RunError as the host throws them.
  RunStats run(const std::vector<std::string>& components) {
    RunContext run;
    run.scenario = &scenario_;
    run.bus = &bus_;
    run.notifier = &notifier_;
    run.mode = mode_;
    run.output_dir = output_dir_;
    run.single_process = single_process_;
    run.deploy_label = deploy_label_;
    run.assigned_producers = assigned_;
    run.produced_instances = produced_;
    HostOptions options = options_;
    options.components = {"feeder"};
    options.components.insert(options.components.end(), components.begin(), components.end());
    Host host(registry_, run, options);
    host.configure();
    return host.run();
  }

  /// run() expecting it to fail with `Error` (ConfigError, RunError): the error's message, or ""
  /// when the run completed. Another exception type propagates (the test fails).
  template <class Error>
  std::string run_error(const std::vector<std::string>& components) {
    try {
      run(components);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }

 private:
  std::string scenario_file_;
  Scenario scenario_;
  ComponentRegistry registry_;
  HostOptions options_;
  TimeMode mode_ = TimeMode::kLockstep;
  bool single_process_ = true;
  std::string deploy_label_;
  std::shared_ptr<const AssignedProducers> assigned_;
  std::shared_ptr<const ProducedInstances> produced_;
  Notifier notifier_;
  MemoryBus bus_;
  std::string output_dir_;
  std::function<void(std::uint64_t)> feed_;
  std::vector<std::shared_ptr<void>> records_;
  std::vector<std::shared_ptr<ReaderHandle>> readers_;
};

/// Samples of `samples` whose key is `key`, in order.
template <class Msg>
std::vector<Msg> of_instance(const std::vector<Msg>& samples, std::uint64_t key) {
  std::vector<Msg> out;
  for (const Msg& s : samples) {
    if (idl::instance_key(s) == key) {
      out.push_back(s);
    }
  }
  return out;
}

/// The samples of one robot (robot_id), whatever the rest of their key (e.g. target_id), in order.
template <class Msg>
std::vector<Msg> of_robot(const std::vector<Msg>& samples, std::uint32_t robot_id) {
  std::vector<Msg> out;
  for (const Msg& s : samples) {
    if (s.robot_id() == robot_id) {
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace robodds::testing
