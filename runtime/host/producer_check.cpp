#include "runtime/host/producer_check.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "common/number_text.hpp"
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
  ComponentTopics out{bus.topics, bus.read_topics, context.records_run(), context.declared_instances(), std::nullopt, "", {}};
  if (!context.rate_key().empty()) {
    out.period_s = static_cast<double>(context.period_steps()) * scenario.step_s;
    out.rate_key = context.rate_key();
  }
  out.rate_assumptions = context.rate_assumptions();
  return out;
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

ScenarioProducers producers_of(const std::map<std::string, ComponentTopics>& components) {
  ScenarioProducers producers;
  for (const auto& [name, topics] : components) {
    producers[name] = topics.publishes;
  }
  return producers;
}

ScenarioProducers scenario_producers(const ComponentRegistry& registry, const Scenario& scenario, TimeMode mode) {
  return producers_of(scenario_component_topics(registry, scenario, mode));
}

namespace {

/// "10 Hz" of a period in s (to 6 significant figures: 1 / (10 x 0.01) is not exactly 10).
std::string hz_text(double period_s) {
  const double hz = 1.0 / period_s;
  const double scale = std::pow(10.0, 5 - std::floor(std::log10(hz)));
  return shortest_text(std::round(hz * scale) / scale) + " Hz";
}

std::string seconds_text(double s) { return shortest_text(std::round(s * 1e6) / 1e6) + " s"; }

bool reads_from(const std::vector<std::uint32_t>& producer_robots, const std::vector<std::uint32_t>& read) {
  return std::any_of(read.begin(), read.end(), [&](std::uint32_t r) {
    return std::find(producer_robots.begin(), producer_robots.end(), r) != producer_robots.end();
  });
}

}  // namespace

std::vector<std::string> check_input_rates(const Scenario& scenario, const std::map<std::string, ComponentTopics>& components,
                                           TimeMode mode) {
  using Kind = InputRateAssumption::Kind;
  std::vector<std::string> warnings;
  for (const ComponentSpec& consumer : scenario.components) {
    const auto c = components.find(consumer.name);
    if (c == components.end()) {
      continue;
    }
    for (const InputRateAssumption& a : c->second.rate_assumptions) {
      const std::vector<std::uint32_t>& read = a.robots.empty() ? consumer.robots : a.robots;
      const TopicInfo& info = topic_info(a.topic);
      const bool unkeyed = info.key == "-" || info.key.empty();
      for (const ComponentSpec& producer : scenario.components) {
        const auto p = components.find(producer.name);
        if (p == components.end() || p->second.publishes.count(a.topic) == 0 || !p->second.period_s ||
            (!unkeyed && !reads_from(producer.robots, read))) {
          continue;
        }
        const double produced_s = *p->second.period_s;
        const std::string where = consumer.name + "." + a.key;
        const std::string source = "its producer '" + producer.name + "' samples " + a.topic + " at " + hz_text(produced_s) +
                                   " (" + producer.name + "." + p->second.rate_key + ")";
        const double tolerance_s = 1e-9 * produced_s;
        if (a.kind == Kind::kAgeLimit) {
          const std::string limit = seconds_text(a.value_s) + " judges " + a.topic + " stale";
          const std::string unaffected =
              a.realtime_only && mode != TimeMode::kRealtime ? "; real time only: this lockstep run is not affected" : "";
          if (a.value_s <= produced_s + tolerance_s) {
            const std::string reason = limit + ", but " + source + ", one every " + seconds_text(produced_s) +
                                       ": the input would be stale between any two samples (raise " + a.key + " to " +
                                       seconds_text(2.0 * produced_s) + " or more, or the producer's rate)";
            if (!a.realtime_only || mode == TimeMode::kRealtime) {
              throw ConfigError(located(scenario.file, where, reason));
            }
            warnings.push_back(located(scenario.file, where, reason + unaffected));
          } else if (a.value_s < 2.0 * produced_s - tolerance_s) {
            warnings.push_back(located(scenario.file, where,
                                       limit + ", less than two of its producer's periods: " + source +
                                           ", so one lost sample makes it stale" + unaffected));
          }
          continue;
        }
        if (!c->second.period_s) {
          continue;  // a consumer without a rate of its own assumes none
        }
        const double own_s = *c->second.period_s;
        const std::string own = consumer.name + " runs at " + hz_text(own_s);
        if (produced_s > own_s + tolerance_s) {
          const std::string reason = own + " and assumes " + a.topic + (a.kind == Kind::kSameRate ? " at that rate" : " at least at that rate") +
                                     ", but " + source + ": " + std::to_string(static_cast<long long>(std::llround(produced_s / own_s)) - 1) +
                                     " of its steps in " + std::to_string(static_cast<long long>(std::llround(produced_s / own_s))) +
                                     " have no new sample";
          if (a.kind == Kind::kSameRate) {
            throw ConfigError(located(scenario.file, where,
                                      reason + " and would pass the last one on as new; give both the same rate"));
          }
          warnings.push_back(located(scenario.file, where, reason));
        } else if (a.kind == Kind::kSameRate && produced_s < own_s - tolerance_s) {
          warnings.push_back(located(scenario.file, where,
                                     own + " and assumes " + a.topic + " at that rate, but " + source +
                                         ": it takes several samples per step"));
        }
      }
    }
  }
  return warnings;
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
