#pragma once
// The checked-in config/<name>.params.yaml of every registered component type is generated
// from its parameter table (ComponentType::params). These functions render, compare and write
// them; the drift test (params_files_test.cpp) and robodds_regenerate_params use them.

#include <string>

#include "runtime/component/registry.hpp"

namespace robodds {

/// The text config/<name>.params.yaml must have.
std::string expected_params_file(const ComponentType& type);

/// A line diff ("-" lines of `checked_in`, "+" lines of `expected`), "" if equal.
std::string params_file_diff(const std::string& checked_in, const std::string& expected);

/// What `robodds components --params NAME` prints: the type's summary and a table of its
/// parameters (key, type, default, unit, range, description), or with `yaml` its defaults file.
/// An unknown NAME is a ConfigError naming the known types.
std::string component_params_text(const ComponentRegistry& registry, const std::string& name, bool yaml);

/// The command that rewrites every defaults file from the tables.
inline constexpr const char* kRegenerateParamsCommand = "scripts/regenerate_params.sh";

}  // namespace robodds
