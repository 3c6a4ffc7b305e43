#pragma once
// The set-up every node test repeats, once: the text of a small scenario (ScenarioText) and a
// NodeHarness with the component type under test registered (ComponentHarness). A node test
//   ROBODDS_DECLARE_COMPONENT(plant);
//   using Harness = robodds::testing::ComponentHarness<robodds::component_registration::register_plant>;
//   Harness h(ScenarioText("plant_node", 0.01, 0.05).robots({1, 2}).component("{name: plant, type: plant}"));
// then feeds, records and runs as with NodeHarness (runtime/testing/node_harness.hpp).
// Test-only: link robodds_node_harness.

#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "common/number_text.hpp"
#include "runtime/component/registry.hpp"
#include "runtime/testing/node_harness.hpp"

namespace robodds::testing {

/// The text of a scenario file for a node test: name, step_s, duration_s, seed (1 unless seed()),
/// then the facts:, robots: and components: entries in the order they were added. Entries are
/// YAML flow text, written as they read in a scenario file. Converts to the std::string that
/// NodeHarness takes.
class ScenarioText {
 public:
  ScenarioText(std::string name, double step_s, double duration_s)
      : name_(std::move(name)), step_s_(step_s), duration_s_(duration_s) {}

  ScenarioText& seed(std::uint64_t seed) {
    seed_ = seed;
    return *this;
  }
  /// One entry of the top-level facts: map, e.g. "robot_body: {max_speed_mps: 1.0}".
  ScenarioText& fact(const std::string& entry) {
    facts_.push_back(entry);
    return *this;
  }
  /// Robots with these ids and nothing else: "{id: N}" each.
  ScenarioText& robots(std::initializer_list<std::uint32_t> ids) {
    for (std::uint32_t id : ids) {
      robots_.push_back("{id: " + std::to_string(id) + "}");
    }
    return *this;
  }
  /// One robot entry, e.g. "{id: 2, x: 5.0, y: 0.0, theta: 1.5707963267948966}".
  ScenarioText& robot(const std::string& entry) {
    robots_.push_back(entry);
    return *this;
  }
  /// One component entry, e.g. "{name: plant, type: plant, params: {command_timeout_s: 0.2}}".
  ScenarioText& component(const std::string& entry) {
    components_.push_back(entry);
    return *this;
  }

  std::string yaml() const {
    std::string out = "name: " + name_ + "\nstep_s: " + shortest_text(step_s_) + "\nduration_s: " +
                      shortest_text(duration_s_) + "\nseed: " + std::to_string(seed_) + "\n";
    append_section(out, "facts", facts_, "  ");
    append_section(out, "robots", robots_, "  - ");
    append_section(out, "components", components_, "  - ");
    return out;
  }
  /// Implicit, so that a harness is made from it directly: Harness h(ScenarioText(...)...).
  operator std::string() const { return yaml(); }

 private:
  static void append_section(std::string& out, const char* key, const std::vector<std::string>& entries, const char* prefix) {
    if (entries.empty()) {
      return;
    }
    out += std::string(key) + ":\n";
    for (const std::string& entry : entries) {
      out += prefix + entry + "\n";
    }
  }

  std::string name_;
  double step_s_;
  double duration_s_;
  std::uint64_t seed_ = 1;
  std::vector<std::string> facts_;
  std::vector<std::string> robots_;
  std::vector<std::string> components_;
};

/// A NodeHarness with one component type registered: `Register` is the
/// robodds::component_registration::register_<type> that ROBODDS_DECLARE_COMPONENT(<type>) declares.
template <void (*Register)(ComponentRegistry&)>
class ComponentHarness : public NodeHarness {
 public:
  explicit ComponentHarness(const std::string& scenario_yaml) : NodeHarness(scenario_yaml) { Register(registry()); }
};

}  // namespace robodds::testing
