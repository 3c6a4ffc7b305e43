#pragma once
// What a metrics module (metrics_module.hpp) sees of the run while it configures: the recorded
// topics, the facts it may need (step, robots, metrics_after_s, the scenario for its shared
// facts), and the ways to take part in the recording: a callback per sample of a topic, a topic
// recorded for every robot, or a topic the module records itself.

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/component/component.hpp"
#include "sim/evaluator/module/recorder.hpp"

namespace robodds::evaluator {

class MetricsSetup {
 public:
  /// Makes the recorder of a topic a module records itself; called by the core in topic order.
  using RecorderFactory = std::function<std::unique_ptr<RecorderBase>()>;

  MetricsSetup(ComponentContext& ctx, std::vector<std::string> topics, double metrics_after_s)
      : ctx_(ctx), topics_(std::move(topics)), metrics_after_s_(metrics_after_s) {}

  /// The evaluator's `topics` parameter, in its order.
  const std::vector<std::string>& topics() const { return topics_; }
  bool recorded(const std::string& topic) const;
  double step_s() const { return ctx_.step_s(); }
  /// Error statistics ignore samples before this time (s) ...
  double metrics_after_s() const { return metrics_after_s_; }
  /// ... that is, before this step.
  std::uint64_t metrics_from_step() const {
    return static_cast<std::uint64_t>(std::llround(metrics_after_s_ / ctx_.step_s()));
  }
  /// The robots this evaluator serves (summary.json metrics.robots), in key order.
  std::vector<std::uint64_t> served_robots() const { return ctx_.robot_keys(); }
  /// Every robot of the scenario, in the scenario's order.
  std::vector<std::uint32_t> scenario_robots() const;
  /// For the scenario's shared facts (system/robot_facts.hpp).
  const Scenario& scenario() const { return ctx_.scenario(); }
  const std::string& component_name() const { return ctx_.name(); }
  /// A ConfigError naming the evaluator's parameters; `message` starts with "key: ".
  [[noreturn]] void fail(const std::string& message) const { ctx_.params().fail(message); }

  /// Calls `callback` with every sample of `topic` as it is recorded (nothing if the topic is not
  /// recorded). Msg must be the topic's type in the catalog.
  template <class Msg>
  void on(const std::string& topic, std::function<void(const Msg&)> callback) {
    std::unique_ptr<CallbacksBase>& slot = callbacks_[topic];
    if (!slot) {
      slot = std::make_unique<Callbacks<Msg>>();
    }
    auto* typed = dynamic_cast<Callbacks<Msg>*>(slot.get());
    if (typed == nullptr) {
      throw std::logic_error("evaluator: two metrics modules attach callbacks of different types to '" + topic + "'");
    }
    typed->list.push_back(std::move(callback));
  }
  /// Records `topic` for every robot of the scenario, not only the served ones (a module that
  /// needs the peers' samples too).
  void record_every_robot(const std::string& topic) { every_robot_.insert(topic); }
  /// Records `topic` with the module's own recorder (its rows need more than the sample), made
  /// by `make` when the core reaches the topic.
  void record_own(const std::string& topic, RecorderFactory make);
  /// A subscription for a recorder made by a RecorderFactory.
  template <class Msg>
  Input<Msg>& subscribe(const std::string& topic, const Subscription& subscription) {
    return ctx_.subscribe<Msg>(topic, subscription);
  }

  // For the core, once every module is configured.
  bool records_every_robot(const std::string& topic) const { return every_robot_.count(topic) > 0; }
  /// The factory of a topic a module records itself, nullptr if none.
  const RecorderFactory* own_recorder(const std::string& topic) const;
  /// The callbacks attached to `topic`, whose catalog type is Msg (std::logic_error if a module
  /// attached another type).
  template <class Msg>
  std::vector<std::function<void(const Msg&)>> take_callbacks(const std::string& topic) {
    const auto it = callbacks_.find(topic);
    if (it == callbacks_.end()) {
      return {};
    }
    auto* typed = dynamic_cast<Callbacks<Msg>*>(it->second.get());
    if (typed == nullptr) {
      throw std::logic_error("evaluator: a metrics module attaches a callback of another type than the catalog's to '" + topic + "'");
    }
    return std::move(typed->list);
  }

 private:
  struct CallbacksBase {
    virtual ~CallbacksBase() = default;
  };
  template <class Msg>
  struct Callbacks : CallbacksBase {
    std::vector<std::function<void(const Msg&)>> list;
  };

  ComponentContext& ctx_;
  std::vector<std::string> topics_;
  double metrics_after_s_;
  std::map<std::string, std::unique_ptr<CallbacksBase>> callbacks_;  // topic -> Callbacks<its type>
  std::set<std::string> every_robot_;
  std::map<std::string, RecorderFactory> own_recorders_;
};

}  // namespace robodds::evaluator
