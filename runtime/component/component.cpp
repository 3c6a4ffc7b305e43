#include "runtime/component/component.hpp"

#include <cmath>

#include "common/did_you_mean.hpp"
#include "common/random.hpp"
#include "runtime/config/param_table_reader.hpp"
#include "runtime/component/registry.hpp"

namespace robodds {

std::function<bool(std::uint64_t, std::uint32_t)> ComponentContext::assigned_producer_rule(const std::string& topic) const {
  // A topic the scenario gives no producer at all, like an instance it gives none (a robot
  // commanded from outside: docs/interop.md), keeps the first writer rule.
  const auto topic_producers = run_.assigned_producers ? run_.assigned_producers->find(topic)
                                                       : AssignedProducers::const_iterator{};
  if (!run_.assigned_producers || topic_producers == run_.assigned_producers->end()) {
    return {};
  }
  const Bus* bus = run_.bus;
  // The map lives as long as the rule: it holds the shared pointer.
  return [bus, assigned = run_.assigned_producers, producers = &topic_producers->second](std::uint64_t writer_id,
                                                                                          std::uint32_t robot) {
    const auto it = producers->find(robot);
    return it == producers->end() || bus->writer_runs_any(writer_id, it->second);
  };
}

std::vector<RobotSpec> ComponentContext::robots() const {
  std::vector<RobotSpec> out;
  for (std::uint32_t id : spec_.robots) {
    out.push_back(run_.scenario->robot(id));
  }
  return out;
}

std::vector<std::uint64_t> ComponentContext::robot_keys() const {
  return std::vector<std::uint64_t>(spec_.robots.begin(), spec_.robots.end());
}

std::uint64_t ComponentContext::seed_for(const std::string& stream) const {
  return derive_seed(run_.scenario->seed, spec_.name + "/" + stream);
}

void ComponentContext::set_rate_hz(double rate_hz, const std::string& key) {
  const double steps = 1.0 / (rate_hz * step_s());
  const double rounded = std::round(steps);
  if (!(rate_hz > 0.0) || rounded < 1.0 || std::abs(steps - rounded) > 1e-6 * steps) {
    params_.fail(key + ": " + std::to_string(rate_hz) + " Hz is not the simulation rate (" +
                 std::to_string(1.0 / step_s()) + " Hz) divided by a whole number");
  }
  state_->period_steps = static_cast<std::uint64_t>(rounded);
  rate_key_ = key;
}

void ComponentContext::expects_rate_of(const std::string& topic, const std::string& key, InputRateAssumption::Kind kind,
                                       std::vector<std::uint32_t> robots) {
  rate_assumptions_.push_back(InputRateAssumption{kind, topic, key, 0.0, false, std::move(robots)});
}

void ComponentContext::limits_age_of(const std::string& topic, const std::string& key, double value_s, bool realtime_only,
                                     std::vector<std::uint32_t> robots) {
  rate_assumptions_.push_back(
      InputRateAssumption{InputRateAssumption::Kind::kAgeLimit, topic, key, value_s, realtime_only, std::move(robots)});
}

void ComponentContext::require_longer_than_period(const std::string& key, double value_s) {
  const double period_s = static_cast<double>(state_->period_steps) * step_s();
  if (!(value_s > period_s)) {
    params_.fail(key + ": must be longer than the component's period (" + std::to_string(period_s) + " s), is " +
                 std::to_string(value_s));
  }
}

ParamReader scenario_component_params(const ComponentType& type, const ComponentSpec& spec) {
  const FlatParams defaults = default_params(type.params(), "built-in defaults of " + type.name);
  return ParamReader(spec.name, merge_params(defaults, spec.overrides));
}

void ComponentRegistry::add_scenario_check(std::function<void(const Scenario&)> check) {
  scenario_checks_.push_back(std::move(check));
}

void ComponentRegistry::check_scenario(const Scenario& scenario) const {
  for (const auto& check : scenario_checks_) {
    check(scenario);
  }
}

void ComponentRegistry::add(ComponentType type) {
  if (type.name.empty() || !type.create || !type.params) {
    throw ConfigError("component type '" + type.name + "': a registration needs a name, a factory and a parameter table");
  }
  for (const ComponentType& known : types_) {
    if (known.name == type.name) {
      throw ConfigError("component type '" + type.name + "' is registered twice");
    }
  }
  types_.push_back(std::move(type));
}

const ComponentType& ComponentRegistry::get(const std::string& name) const {
  std::string known;
  std::vector<std::string> names;
  for (const ComponentType& type : types_) {
    if (type.name == name) {
      return type;
    }
    known += (known.empty() ? "" : ", ") + type.name;
    names.push_back(type.name);
  }
  throw ConfigError("unknown component type '" + name + "'" + did_you_mean(name, names) + " (known: " + known + ")");
}

const ComponentType& ComponentRegistry::type_of(const Scenario& scenario, const ComponentSpec& component) const {
  try {
    return get(component.type);
  } catch (const ConfigError& e) {
    throw ConfigError(scenario.file + ": components." + component.name + ".type: " + e.what());
  }
}

}  // namespace robodds
