#pragma once
// Reads a component's parameters through its ParamTable (common/param_table.hpp): the table
// gives the key set, each key's type and its built-in default, so a node's configure() is one
// call and no defaults file is needed at run time.
//
//   const PfEstimatorNodeParams params = read_params(ctx.params(), pf_estimator_param_table());
//   ctx.params().validate(params.filter);  // cross-field rules
//
// Type errors and range errors name the file the value came from, the key and the reason.

#include <string>

#include "common/param_table.hpp"
#include "runtime/config/params.hpp"

namespace robodds {

/// The table's defaults as FlatParams, each remembering `origin` as its "file" (what an error
/// about a value nobody overrode names), e.g. "built-in defaults of plant".
FlatParams default_params(const params::ParamDoc& doc, const std::string& origin);

/// One key read as the given kind (enums as their name); type errors are ConfigErrors.
params::ParamValue read_param_value(ParamReader& reader, const std::string& key, params::ParamKind kind);

/// Reads every key of the table into `out` and runs each key's range check; a failure is a
/// ConfigError naming the key's file. Cross-field rules are the caller's validate() call.
template <class S>
void read_params(ParamReader& reader, const params::ParamTable<S>& table, S& out) {
  for (const params::TableEntry<S>& entry : table.entries()) {
    const params::ParamValue value = read_param_value(reader, entry.info.key, entry.kind);
    reader.check([&] {
      entry.set(out, value);
      entry.check(out);
    });
  }
}

template <class S>
S read_params(ParamReader& reader, const params::ParamTable<S>& table) {
  S out{};
  read_params(reader, table, out);
  return out;
}

}  // namespace robodds
