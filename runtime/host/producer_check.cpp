#include "runtime/host/producer_check.hpp"

#include <algorithm>
#include <memory>
#include <vector>

#include "runtime/component/component.hpp"
#include "runtime/base/error.hpp"
#include "runtime/bus/memory_bus.hpp"
#include "runtime/topics/topic_catalog.hpp"

namespace robodds {
namespace {

/// A MemoryBus that remembers the topics of the writers and readers asked for.
class RecordingBus : public MemoryBus {
 public:
  std::shared_ptr<WriterHandle> writer(const std::string& topic, const std::string& type_name,
                                       const std::string& profile) override {
    topics.insert(topic);
    return MemoryBus::writer(topic, type_name, profile);
  }
  std::shared_ptr<ReaderHandle> reader(const std::string& topic, const std::string& type_name, const std::string& profile,
                                       SampleCallback on_sample, ReaderEventCallback on_event) override {
    read_topics.insert(topic);
    return MemoryBus::reader(topic, type_name, profile, std::move(on_sample), std::move(on_event));
  }
  std::set<std::string> topics;
  std::set<std::string> read_topics;
};

/// "robot_id=3" for a keyed topic, "the topic's one instance" for an unkeyed one.
std::string instance_text(const TopicInfo& topic, std::uint32_t robot) {
  if (topic.key == "-" || topic.key.empty()) {
    return "its one instance (unkeyed)";
  }
  const std::string first = topic.key.substr(0, topic.key.find(','));
  const bool pair = topic.key.find(',') != std::string::npos;
  return first + "=" + std::to_string(robot) + (pair ? " (every pair of that robot)" : "");
}

/// Configures `spec` on its own RecordingBus (nothing runs) and returns what it declared.
ComponentTopics dry_configure(const ComponentRegistry& registry, const Scenario& scenario, const ComponentSpec& spec,
                              TimeMode mode) {
  const ComponentType& type = registry.get(spec.type);
  RecordingBus bus;
  Notifier notifier;
  RunContext run;
  run.scenario = &scenario;
  run.bus = &bus;
  run.notifier = &notifier;
  run.mode = mode;
  StepState state;
  state.mode = mode;
  ComponentContext context(run, spec, scenario_component_params(type, spec), &state);
  std::unique_ptr<Component> component = type.create();
  component->configure(context);
  return ComponentTopics{bus.topics, bus.read_topics, context.records_run(), context.declared_instances()};
}

}  // namespace

std::map<std::string, ComponentTopics> scenario_component_topics(const ComponentRegistry& registry, const Scenario& scenario,
                                                                 TimeMode mode) {
  std::map<std::string, ComponentTopics> topics;
  for (const ComponentSpec& spec : scenario.components) {
    topics[spec.name] = dry_configure(registry, scenario, spec, mode);
  }
  return topics;
}

ProducedInstances produced_instances(const ComponentRegistry& registry, const Scenario& scenario,
                                     const ScenarioProducers& producers, TimeMode mode) {
  std::map<std::string, std::set<std::uint64_t>> found;
  for (const ComponentSpec& spec : scenario.components) {
    const auto it = producers.find(spec.name);
    const bool two_member_key = it != producers.end() && std::any_of(it->second.begin(), it->second.end(), [](const std::string& t) {
                              return topic_info(t).key.find(',') != std::string::npos;
                            });
    if (!two_member_key) {
      continue;  // its instances are its robots (or the one of an unkeyed topic): nothing to declare
    }
    for (const auto& [topic, keys] : dry_configure(registry, scenario, spec, mode).instances) {
      found[topic].insert(keys.begin(), keys.end());
    }
  }
  ProducedInstances out;
  for (const auto& [topic, keys] : found) {
    out[topic].assign(keys.begin(), keys.end());  // std::set: ascending, once each
  }
  return out;
}

ScenarioProducers scenario_producers(const ComponentRegistry& registry, const Scenario& scenario, TimeMode mode) {
  ScenarioProducers producers;
  for (auto& [name, topics] : scenario_component_topics(registry, scenario, mode)) {
    producers[name] = std::move(topics.publishes);
  }
  return producers;
}

namespace {

/// Calls fn(spec, topic, robot) for every instance each component of the scenario publishes
/// (robot 0: an unkeyed topic's one instance), components in scenario order.
template <class Fn>
void for_each_produced_instance(const Scenario& scenario, const ScenarioProducers& producers, Fn&& fn) {
  for (const ComponentSpec& spec : scenario.components) {
    auto it = producers.find(spec.name);
    if (it == producers.end()) {
      continue;
    }
    for (const std::string& topic : it->second) {
      const TopicInfo& info = topic_info(topic);
      const bool unkeyed = info.key == "-" || info.key.empty();
      for (std::uint32_t robot : unkeyed ? std::vector<std::uint32_t>{0} : spec.robots) {
        fn(spec, topic, info, robot);
      }
    }
  }
}

}  // namespace

AssignedProducers assigned_producers(const Scenario& scenario, const ScenarioProducers& producers) {
  AssignedProducers assigned;
  for_each_produced_instance(scenario, producers,
                             [&assigned](const ComponentSpec& spec, const std::string& topic, const TopicInfo&, std::uint32_t robot) {
                               assigned[topic][robot].push_back(spec.name);
                             });
  return assigned;
}

void check_one_producer_per_instance(const Scenario& scenario, const ScenarioProducers& producers) {
  // (topic, robot or 0 for unkeyed) -> the first component publishing it.
  std::map<std::pair<std::string, std::uint32_t>, const ComponentSpec*> owner;
  for_each_produced_instance(scenario, producers, [&](const ComponentSpec& spec, const std::string& topic, const TopicInfo& info,
                                                      std::uint32_t robot) {
    if (!spec.standby_for.empty()) {
      return;  // a hot standby shares its primary's instances by design (exclusive ownership)
    }
    auto [slot, inserted] = owner.emplace(std::make_pair(topic, robot), &spec);
    if (!inserted) {
      const ComponentSpec& first = *slot->second;
      throw ConfigError(located(scenario.file, "components",
                                "topic " + topic + ", " + instance_text(info, robot) + ": published by both '" + first.name +
                                    "' (" + first.type + ") and '" + spec.name + "' (" + spec.type +
                                    "); one producer per topic instance (give them different robots, or declare "
                                    "a hot standby with standby_for)"));
    }
  });
}

void check_standby_deployment(const Scenario& scenario, TimeMode mode, bool single_process) {
  for (const ComponentSpec& spec : scenario.components) {
    if (spec.standby_for.empty()) {
      continue;
    }
    if (mode == TimeMode::kLockstep) {
      throw ConfigError(located(scenario.file, spec.name + ".standby_for",
                                "a hot standby runs in real time only (--realtime): in lockstep its samples would "
                                "duplicate its primary's; remove the standby for lockstep runs"));
    }
    if (single_process) {
      throw ConfigError(located(scenario.file, spec.name + ".standby_for",
                                "a hot standby needs one process per group (--deploy processes or robodds host per "
                                "group): in one process it dies with its primary"));
    }
  }
}

void check_standby_apart(const Scenario& scenario, const std::vector<std::string>& components) {
  const std::set<std::string> here(components.begin(), components.end());
  for (const std::string& name : components) {
    const ComponentSpec& spec = scenario.component(name);
    if (!spec.standby_for.empty() && here.count(spec.standby_for) != 0) {
      throw ConfigError(located(scenario.file, name + ".standby_for",
                                "the standby '" + name + "' and its primary '" + spec.standby_for +
                                    "' would run in one process, and die together; run them in separate hosts"));
    }
  }
}

std::set<std::string> exclusive_topics(const Scenario& scenario, const ScenarioProducers& producers) {
  std::set<std::string> topics;
  for (const ComponentSpec& spec : scenario.components) {
    auto it = producers.find(spec.name);
    if (!spec.standby_for.empty() && it != producers.end()) {
      topics.insert(it->second.begin(), it->second.end());
    }
  }
  return topics;
}

void apply_exclusive_ownership(Bus& bus, const Scenario& scenario, const ScenarioProducers& producers,
                               const std::set<std::string>& exclusive, const std::vector<std::string>& components) {
  for (const std::string& topic : exclusive) {
    std::uint32_t strength = kPrimaryStrength;
    for (const std::string& name : components) {
      auto it = producers.find(name);
      if (!scenario.component(name).standby_for.empty() && it != producers.end() && it->second.count(topic) != 0) {
        strength = kStandbyStrength;
      }
    }
    bus.set_exclusive_ownership(topic, strength);
  }
}

}  // namespace robodds
