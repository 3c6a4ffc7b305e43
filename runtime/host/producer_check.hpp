#pragma once
// One producer per topic instance (docs/architecture.md, "One producer per instance and hot
// standby"), checked before anything runs: which topics each component of a scenario publishes,
// found by configuring it on a MemoryBus (ComponentContext::advertise is the one place a
// component declares an output, so nothing can disagree with the code), and the instances it
// publishes them for (its robots).

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "runtime/bus/bus.hpp"
#include "runtime/component/component.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/config/scenario.hpp"

namespace robodds {

/// Component instance name -> topics it publishes.
using ScenarioProducers = std::map<std::string, std::set<std::string>>;

/// Configures each component of `scenario` on its own MemoryBus (no DDS, no files, nothing
/// runs) in time mode `mode` and records the topics it advertises. A component's ConfigError
/// propagates (it would stop the run anyway).
ScenarioProducers scenario_producers(const ComponentRegistry& registry, const Scenario& scenario, TimeMode mode);

/// Who may publish each topic instance of the scenario (RunContext::assigned_producers): the
/// component that publishes the topic for that robot (a pair-keyed topic: for the first key's
/// robot; an unkeyed topic: robot 0), and a hot standby of it.
AssignedProducers assigned_producers(const Scenario& scenario, const ScenarioProducers& producers);

/// What one component instance writes and reads on the bus (its DDS endpoints, for DDS Security
/// permissions): found like scenario_producers(), with readers recorded too.
struct ComponentTopics {
  std::set<std::string> publishes;
  std::set<std::string> subscribes;
  bool wants_run_health = false;  // its host reads run/health across processes
  ProducedInstances instances;     // ComponentContext::publishes_instances(): topic -> keys
  /// Its period (s) and the parameter that set it (ComponentContext::set_rate_hz()); nullopt: it
  /// set no rate (it runs every step and its rate says nothing of its samples').
  std::optional<double> period_s;
  std::string rate_key;
  std::vector<InputRateAssumption> rate_assumptions;  // ComponentContext::expects_rate_of(), limits_age_of()
};
/// Component instance name -> its topics, in time mode `mode`.
std::map<std::string, ComponentTopics> scenario_component_topics(const ComponentRegistry& registry, const Scenario& scenario,
                                                                 TimeMode mode);
/// The topics each component publishes, from scenario_component_topics() (what
/// scenario_producers() returns).
ScenarioProducers producers_of(const std::map<std::string, ComponentTopics>& components);

/// The rate assumptions each component declared on its inputs (InputRateAssumption) against the
/// rates of the scenario's producers of those inputs (those serving a robot whose instances it
/// reads): ConfigError, one line naming the scenario file, both components, their keys and both
/// rates, for the first mismatch that breaks an assumption (a producer slower than a kSameRate
/// consumer; an age limit not longer than the producer's period, where the limit applies in time
/// mode `mode`); the mismatches that are legitimate but worth knowing are returned as warning
/// lines, in scenario order. Producers that set no rate are not judged.
std::vector<std::string> check_input_rates(const Scenario& scenario, const std::map<std::string, ComponentTopics>& components,
                                           TimeMode mode);

/// The instances the components of `scenario` declare for the topics they publish
/// (ComponentContext::publishes_instances(), RunContext::produced_instances): each topic's keys
/// over all its producers, ascending, once each. Only the components that publish a topic keyed by
/// two members (the ones that may declare) are configured again, on a MemoryBus, in time mode `mode`.
ProducedInstances produced_instances(const ComponentRegistry& registry, const Scenario& scenario,
                                     const ScenarioProducers& producers, TimeMode mode);

/// ConfigError (one line naming the scenario file, the topic, the instance and both components)
/// if two components that are not standbys publish one topic for one instance. Instances: a
/// robot-keyed topic's instances are the component's robots; a pair-keyed topic (robot_id,
/// target_id / peer_id) is published by the component serving the first key's robot, so two
/// producers of pairs of one robot conflict; an unkeyed topic has one instance.
void check_one_producer_per_instance(const Scenario& scenario, const ScenarioProducers& producers);

/// ConfigError naming the file and the standby unless standbys may run: real time and one
/// process per group (a standby beside its primary dies with it; lockstep has no hand-over).
void check_standby_deployment(const Scenario& scenario, TimeMode mode, bool single_process);

/// ConfigError naming the file, the standby and its primary if `components` (one process's,
/// e.g. `robodds host --components`) holds both: they would die together.
void check_standby_apart(const Scenario& scenario, const std::vector<std::string>& components);

/// Topics a standby publishes: their readers and writers use exclusive ownership.
std::set<std::string> exclusive_topics(const Scenario& scenario, const ScenarioProducers& producers);

/// Ownership strength of this process's writers: a primary's outweighs its standby's.
inline constexpr std::uint32_t kPrimaryStrength = 2;
inline constexpr std::uint32_t kStandbyStrength = 1;

/// Calls bus.set_exclusive_ownership() for each exclusive topic with the strength of the
/// writers of `components` (this process's): kStandbyStrength if a standby among them publishes
/// the topic, kPrimaryStrength otherwise.
void apply_exclusive_ownership(Bus& bus, const Scenario& scenario, const ScenarioProducers& producers,
                               const std::set<std::string>& exclusive, const std::vector<std::string>& components);

}  // namespace robodds
