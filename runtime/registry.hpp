#pragma once
// Component types by name. Registration is explicit (register_builtin_components() in the
// components library) rather than by static initialisers, which static linking drops.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/param_doc.hpp"
#include "runtime/component.hpp"

namespace robodds {

struct ComponentType {
  std::string name;
  std::string description;
  std::string defaults_file;  // generated from `params`, relative to the share dir, e.g. sim/plant/config/plant.params.yaml
  std::function<std::unique_ptr<Component>()> create;
  /// Its parameters from its parameter table: the key set, types and defaults the host reads
  /// (defaults_file is their generated, documented copy), and `robodds components --params`.
  std::function<params::ParamDoc()> params;
};

class ComponentRegistry {
 public:
  void add(ComponentType type);
  /// Throws ConfigError naming the unknown type and the known ones.
  const ComponentType& get(const std::string& name) const;
  const std::vector<ComponentType>& types() const { return types_; }

 private:
  std::vector<ComponentType> types_;
};

}  // namespace robodds
