#include "runtime/config/param_table_reader.hpp"

namespace robodds {

FlatParams default_params(const params::ParamDoc& doc, const std::string& origin) {
  FlatParams out;
  for (const params::ParamInfo& info : doc.params) {
    out[info.key] = ParamEntry{info.default_yaml, origin};
  }
  return out;
}

params::ParamValue read_param_value(ParamReader& reader, const std::string& key, params::ParamKind kind) {
  switch (kind) {
    case params::ParamKind::kDouble:
      return reader.get_double(key);
    case params::ParamKind::kInt:
      return reader.get_int(key);
    case params::ParamKind::kUint:
      return reader.get_uint(key);
    case params::ParamKind::kBool:
      return reader.get_bool(key);
    case params::ParamKind::kString:
    case params::ParamKind::kEnum:
      return reader.get_string(key);
    case params::ParamKind::kDoubleList:
      return reader.get_double_list(key);
    case params::ParamKind::kStringList:
      return reader.get_string_list(key);
    case params::ParamKind::kPointList:
      return reader.get_point_list(key);
  }
  reader.fail(key + ": unsupported parameter type");
}

}  // namespace robodds
