#include "tools/robodds/params_files.hpp"

#include "common/line_diff.hpp"
#include "runtime/base/error.hpp"

namespace robodds {

std::string expected_params_file(const ComponentType& type) { return params::render_params_yaml(type.params()); }

std::string component_params_text(const ComponentRegistry& registry, const std::string& name, bool yaml) {
  const ComponentType& type = registry.get(name);
  if (yaml) {
    return expected_params_file(type);
  }
  const params::ParamDoc doc = type.params();
  std::string text = type.name + ": " + type.description + "\n";
  if (!doc.summary.empty()) {
    text += doc.summary + "\n";
  }
  text += "defaults file: " + type.defaults_file + "\n\n";
  return text + params::describe_params(doc);
}

std::string params_file_diff(const std::string& checked_in, const std::string& expected) {
  if (checked_in == expected) {
    return "";
  }
  const std::string diff = line_diff(checked_in, expected);
  return diff.empty() ? "(the files differ only in their line endings)\n" : diff;
}

}  // namespace robodds
