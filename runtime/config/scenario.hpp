#pragma once
// Scenario files (sim/scenarios/*.yaml): robots, components with parameter overrides, time
// step, duration, seed, and the deployment grouping (which components share a process).

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "runtime/config/params.hpp"

namespace robodds {

struct RobotSpec {
  std::uint32_t id = 0;
  double x = 0.0;      // m, initial position (world)
  double y = 0.0;      // m
  double theta = 0.0;  // rad, initial heading
  /// This robot's own `facts:` (flattened, e.g. "robot_body.wheel_base_m"), over the scenario's.
  FlatParams facts;
};

struct ComponentSpec {
  std::string name;                   // instance name, unique in the scenario
  std::string type;                   // registered component type
  std::vector<std::uint32_t> robots;  // robots it serves (default: all)
  FlatParams overrides;               // scenario values over the type's defaults
  /// Hot standby of the named component (real time, processes only): same type and robots,
  /// another group; its outputs take over when the primary dies (exclusive ownership).
  std::string standby_for;
};

struct GroupSpec {
  std::string name;                     // deployment group = one host process
  std::vector<std::string> components;  // component instance names
};

struct Scenario {
  std::string file;
  std::string name;
  std::string description;
  double step_s = 0.01;
  double duration_s = 10.0;
  std::uint64_t seed = 1;
  std::vector<RobotSpec> robots;
  std::vector<ComponentSpec> components;
  std::vector<GroupSpec> groups;
  /// Top-level sections that the layer above reads (register_scenario_section(): e.g. paper 2's
  /// `targets:` and `events:`, system/mission_plan.hpp), each as its YAML text (flow style) and
  /// the file; the runtime reads none of them.
  std::map<std::string, ParamEntry> sections;
  /// The scenario's `facts:`, flattened ("robot_body.wheel_base_m" -> value and file): what
  /// several components must agree on. The runtime stores them and reads none; the layer above
  /// gives them types and checks them (system/, a ComponentRegistry scenario check).
  FlatParams facts;

  /// Index of the last step: steps 0..last_step() run, at times step * step_s (checked_last_step()).
  std::uint64_t last_step() const;
  const ComponentSpec& component(const std::string& name) const;
  /// How many distinct robots the named components serve together (e.g. one process's: the
  /// instances its robot-keyed writers publish). ConfigError for an unknown name, as component().
  std::size_t robots_served_by(const std::vector<std::string>& component_names) const;
  const GroupSpec& group(const std::string& name) const;
  const RobotSpec& robot(std::uint32_t id) const;
  /// The facts of robot `id`: the scenario's `facts:` with the robot's own `facts:` over them.
  FlatParams facts_of(std::uint32_t id) const;
};

/// Most steps after step 0 a run may have: 2^40 (about 1.1e12: 35 years of simulated time at a
/// 1 ms step, 13 days of wall time at a million ticks per second). A sanity bound far below where
/// round(duration_s / step_s) stops fitting an integer (2^63), so that a slip such as
/// `step_s: 1e-25` or `--duration 1e300` is a clear error, not an overflowed count.
inline constexpr std::uint64_t kMaxLastStep = std::uint64_t{1} << 40;

/// The one step-count rule: round(duration_s / step_s), the index of the last step. Throws
/// ConfigError(located(file, key, reason)) unless step_s and duration_s are positive and finite
/// and the last step is at most kMaxLastStep (the reason names both values and the count).
std::uint64_t checked_last_step(double step_s, double duration_s, const std::string& file, const std::string& key);

/// The command line's --duration and --seed over the scenario's (nullopt: keep the scenario's);
/// a new duration is checked against the step (checked_last_step(), naming --duration).
void apply_run_overrides(Scenario& scenario, const std::optional<double>& duration_s, const std::optional<std::uint64_t>& seed);

/// Lets scenario files have a top-level section `name` that the runtime does not read (stored in
/// Scenario::sections): the layer above declares its sections so, from a static initialiser or
/// before loading; any other unknown key stays an error. Returns true (for static initialisers).
bool register_scenario_section(const std::string& name);

/// Loads and validates a scenario (throws ConfigError naming file, key and reason).
Scenario load_scenario(const std::string& path);

/// Puts `overrides` (keys "<component>.<parameter>", e.g. from load_param_file() of a
/// `robodds host --params` file) on top of the scenario's parameter overrides. A key naming no
/// scenario component is a ConfigError naming the overrides' file and the key. Whether the
/// parameter exists is checked later, against the component type's defaults (merge_params()).
void apply_param_overrides(Scenario& scenario, const FlatParams& overrides, const std::string& file);

}  // namespace robodds
