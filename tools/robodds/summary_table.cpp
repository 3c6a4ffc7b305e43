#include "tools/robodds/summary_table.hpp"

#include <yaml-cpp/yaml.h>

#include <fstream>

namespace robodds {
namespace {

/// A scalar as summary.json has it: strings in quotes, numbers and null bare.
std::string json_text(const YAML::Node& node) {
  if (node.IsNull()) {
    return "null";  // a non-finite figure
  }
  if (node.IsScalar()) {
    return node.Tag() == "!" ? "\"" + node.Scalar() + "\"" : node.Scalar();  // "!": a quoted scalar
  }
  if (node.IsMap() && node.size() == 0) {
    return "{}";
  }
  std::string text = "[";
  for (std::size_t i = 0; i < node.size(); ++i) {
    text += (i == 0 ? "" : ", ") + json_text(node[i]);
  }
  return text + "]";
}

void append_rows(std::string& out, const YAML::Node& map, const std::string& prefix) {
  for (const auto& entry : map) {
    const std::string key = prefix + entry.first.Scalar();
    if (entry.second.IsMap() && entry.second.size() > 0) {
      append_rows(out, entry.second, key + ".");
      continue;
    }
    out += "  " + key + std::string(key.size() < 48 ? 48 - key.size() : 0, ' ') + " " + json_text(entry.second) + "\n";
  }
}

}  // namespace

std::string summary_table(const std::string& out_dir) {
  const std::string path = out_dir + "/summary.json";
  if (!std::ifstream(path)) {
    return "(no summary.json in " + out_dir + ": the scenario has no evaluator)\n";
  }
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);  // JSON is YAML: the parser the project already has
  } catch (const YAML::Exception& e) {
    return "(" + path + " is not valid JSON: " + e.what() + ")\n";
  }
  std::string out = "\nsummary (" + path + ")\n";
  if (root.IsMap()) {
    append_rows(out, root, "");
  }
  return out;
}

}  // namespace robodds
