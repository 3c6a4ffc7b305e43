#pragma once
// The documentation of a component's parameters, type-erased from its ParamTable
// (common/param_table.hpp): what `robodds components --params NAME` prints and what the
// checked-in config/<name>.params.yaml is generated from. Pure: std only.

#include <string>
#include <vector>

namespace robodds::params {

/// One parameter. Every text is ready to print; default_yaml is flow YAML ("100", "[1, 2]").
struct ParamInfo {
  std::string key;  // YAML key, dotted for nested maps ("forward_gains.kd")
  std::string type;  // "double", "int", "bool", "string", "enum", "list of double", ...
  std::string default_yaml;
  std::string unit;   // "m/s", "Hz", ... or "" for dimensionless
  std::string range;  // "> 0", ">= 1", "systematic | residual", ... or "" for any value
  std::string description;  // one line
};

/// A comment for a map of nested keys (printed on the line that opens the map in YAML).
struct ParamGroup {
  std::string prefix;  // e.g. "forward_gains"
  std::string description;
};

struct ParamDoc {
  std::string summary;  // what the component does; may span several lines
  std::vector<ParamGroup> groups;
  std::vector<ParamInfo> params;  // in table order
};

/// The last header line of every generated defaults file.
inline constexpr const char* kGeneratedNote =
    "Generated from the component's parameter table by scripts/regenerate_params.sh; edit the table.";

/// The defaults file: the summary and kGeneratedNote as comment lines, then one `key: default  # unit, range:
/// description` line per parameter (dotted keys as nested maps, in table order). Deterministic.
/// Throws std::invalid_argument if the keys of one nested map are not contiguous.
std::string render_params_yaml(const ParamDoc& doc);

/// A text table: key, type, default, unit, range, description (one row per parameter).
std::string describe_params(const ParamDoc& doc);

}  // namespace robodds::params
