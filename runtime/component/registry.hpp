#pragma once
// Component types by name. A component registers itself in its own folder: its node .cpp says
// ROBODDS_REGISTER_COMPONENT(...) and its CMakeLists.txt calls robodds_component(NAME ...)
// (cmake/RoboddsHelpers.cmake). Registration is explicit rather than by static initialisers,
// which static linking drops: CMake generates registered_components.cpp (build tree), which
// calls each component's registration function in name order from register_builtin_components().

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/param_doc.hpp"
#include "runtime/component/component.hpp"
#include "runtime/config/param_table_reader.hpp"

namespace robodds {

struct ComponentType {
  std::string name;
  std::string description;
  std::string defaults_file;  // generated from `params`, relative to the share dir, e.g. sim/plant/config/plant.params.yaml
  std::function<std::unique_ptr<Component>()> create;
  /// Its parameters from its parameter table: the key set, types and defaults the host reads
  /// (defaults_file is their generated, documented copy), and `robodds components --params`.
  std::function<params::ParamDoc()> params;
  /// Reads every parameter of `reader` through the type's table: a value of the wrong type or out
  /// of its range throws ConfigError naming the file and the key (cross-field rules of the node's
  /// validate() are not run). Lets `robodds sweep` refuse a bad --set value before any run starts.
  std::function<void(ParamReader& reader)> check_params;
};

/// The parameters of the scenario component `spec` of type `type`: the type's defaults (its
/// parameter table) under the scenario's overrides, as its ComponentContext reads them.
ParamReader scenario_component_params(const ComponentType& type, const ComponentSpec& spec);

class ComponentRegistry {
 public:
  /// ConfigError if the type has no name, factory or parameter table, or its name is taken.
  void add(ComponentType type);
  /// Throws ConfigError naming the unknown type and the known ones.
  const ComponentType& get(const std::string& name) const;
  /// The type of a scenario's component; an unknown one throws ConfigError naming the scenario
  /// file and the component (`FILE: components.NAME.type: unknown component type ...`).
  const ComponentType& type_of(const Scenario& scenario, const ComponentSpec& component) const;
  const std::vector<ComponentType>& types() const { return types_; }

  /// A check of the whole scenario by the layer above the runtime (e.g. system/: its shared
  /// facts' keys and values), which the runtime cannot read itself. Each check throws ConfigError
  /// naming the file, the key and the reason.
  void add_scenario_check(std::function<void(const Scenario&)> check);
  /// Runs every scenario check, in the order they were added; before anything starts.
  void check_scenario(const Scenario& scenario) const;

 private:
  std::vector<ComponentType> types_;
  std::vector<std::function<void(const Scenario&)>> scenario_checks_;
};

/// Registers every component type built with robodds_component(), sorted by type name. Defined
/// by the generated registered_components.cpp of the library `robodds_registered_components`
/// (tools/robodds/CMakeLists.txt); link that library to call it.
void register_builtin_components(ComponentRegistry& registry);

}  // namespace robodds

/// Defines robodds::component_registration::register_<type_name>(ComponentRegistry&), which adds
/// the component type `type_name` (a bare identifier, e.g. position_sensor; the scenario's `type`)
/// with a one-line description, its factory (std::unique_ptr<Component>()) and the accessor of
/// its parameter table (`const params::ParamTable<S>& f()`, the one source of its parameters'
/// defaults, units, ranges and descriptions; the registry keeps its doc()). Its defaults file
/// is config/<type_name>.params.yaml of the component's folder: robodds_component() passes that
/// path as ROBODDS_COMPONENT_DEFAULTS_FILE. Write it once, at
/// global scope (outside any namespace; elsewhere it does not compile), in the component's node
/// .cpp, and name the same type_name in the folder's robodds_component(NAME ...) call, which
/// makes the generated registered_components.cpp call the function. Example:
///   ROBODDS_REGISTER_COMPONENT(position_sensor, "noisy absolute position: plant/state -> sensor/position",
///                              robodds::position_sensor::make_position_sensor_node,
///                              robodds::position_sensor::position_sensor_param_table);
#define ROBODDS_REGISTER_COMPONENT(type_name, description, factory, param_table)                         \
  namespace robodds::component_registration {                                                            \
  void register_##type_name(::robodds::ComponentRegistry& registry);                                     \
  }                                                                                                      \
  void ::robodds::component_registration::register_##type_name(::robodds::ComponentRegistry& registry) { \
    registry.add({#type_name, description, ROBODDS_COMPONENT_DEFAULTS_FILE, factory,                     \
                  [] { return param_table().doc(); },                                                    \
                  [](::robodds::ParamReader& reader) { (void)::robodds::read_params(reader, param_table()); }}); \
  }                                                                                                      \
  static_assert(sizeof(description) > 1,                                                                 \
                "ROBODDS_REGISTER_COMPONENT(" #type_name "): the description must not be empty")

/// Declares the registration function of component type `type_name` (defined by its
/// ROBODDS_REGISTER_COMPONENT), at global scope, for code that registers one type by hand: a
/// node's unit test calls robodds::component_registration::register_<type_name>(registry).
#define ROBODDS_DECLARE_COMPONENT(type_name)                       \
  namespace robodds::component_registration {                      \
  void register_##type_name(::robodds::ComponentRegistry& registry); \
  }                                                                \
  static_assert(true, "ROBODDS_DECLARE_COMPONENT needs a semicolon")
