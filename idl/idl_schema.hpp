#pragma once
// The IDL text each topic type needs, for MCAP's `omgidl` schema encoding (robodds record): the
// type's struct plus every struct, enum and typedef it uses, inside their modules, comments
// dropped. Generated at build time from idl/robodds.idl by idl/idl_schemas.py.

#include <string>

namespace robodds {

/// The schema data of the struct `type_name` (fully qualified, "::"-separated, e.g.
/// "robodds::idl::RobotState"); empty if idl/robodds.idl has no such struct.
std::string idl_schema_text(const std::string& type_name);

/// The MCAP schema name of the type: its fully qualified IDL name in "::" form, the root
/// definition @foxglove/omgidl-parser's readers look up among the parsed definitions (their
/// names are the scoped names joined with "::"). Our type names are already in that form.
inline std::string idl_schema_name(const std::string& type_name) { return type_name; }

}  // namespace robodds
