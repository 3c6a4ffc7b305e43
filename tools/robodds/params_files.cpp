#include "tools/robodds/params_files.hpp"

#include <algorithm>
#include <sstream>
#include <vector>

#include "runtime/error.hpp"

namespace robodds {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
  }
  return lines;
}

}  // namespace

std::string expected_params_file(const ComponentType& type) {
  if (!type.params) {
    throw ConfigError("component type '" + type.name + "' has no parameter table (ComponentType::params)");
  }
  return params::render_params_yaml(type.params());
}

std::string component_params_text(const ComponentRegistry& registry, const std::string& name, bool yaml) {
  const ComponentType& type = registry.get(name);
  if (yaml) {
    return expected_params_file(type);
  }
  const params::ParamDoc doc = type.params ? type.params() : params::ParamDoc{};
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
  // Longest common subsequence of lines (the files have a few dozen lines).
  const std::vector<std::string> a = lines_of(checked_in);
  const std::vector<std::string> b = lines_of(expected);
  std::vector<std::vector<std::size_t>> common(a.size() + 1, std::vector<std::size_t>(b.size() + 1, 0));
  for (std::size_t i = a.size(); i-- > 0;) {
    for (std::size_t j = b.size(); j-- > 0;) {
      common[i][j] = a[i] == b[j] ? common[i + 1][j + 1] + 1 : std::max(common[i + 1][j], common[i][j + 1]);
    }
  }
  std::string diff;
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < a.size() || j < b.size()) {
    if (i < a.size() && j < b.size() && a[i] == b[j]) {
      ++i;
      ++j;
    } else if (i < a.size() && (j == b.size() || common[i + 1][j] >= common[i][j + 1])) {
      diff += "-" + a[i++] + "\n";
    } else {
      diff += "+" + b[j++] + "\n";
    }
  }
  return diff.empty() ? "(the files differ only in their line endings)\n" : diff;
}

}  // namespace robodds
