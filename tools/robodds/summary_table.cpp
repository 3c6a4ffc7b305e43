#include "tools/robodds/summary_table.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
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

void append_leaves(std::vector<SummaryLeaf>& out, const YAML::Node& map, const std::string& prefix) {
  for (const auto& entry : map) {
    const std::string key = prefix + entry.first.Scalar();
    if (entry.second.IsMap() && entry.second.size() > 0) {
      append_leaves(out, entry.second, key + ".");
      continue;
    }
    SummaryLeaf leaf{key, json_text(entry.second), std::nullopt};
    if (entry.second.IsScalar() && entry.second.Tag() != "!") {  // "!": a quoted scalar (a string)
      double value = 0.0;
      if (YAML::convert<double>::decode(entry.second, value) && std::isfinite(value)) {
        leaf.number = value;
      }
    }
    out.push_back(std::move(leaf));
  }
}

}  // namespace

bool is_never(const std::string& metric, double value) {
  constexpr double kNever = -1.0;
  return value == kNever && metric.size() >= 2 && metric.compare(metric.size() - 2, 2, "_s") == 0;
}

std::vector<SummaryLeaf> summary_leaves(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);  // JSON is YAML: the parser the project already has
  } catch (const YAML::BadFile&) {
    throw std::runtime_error(path + " cannot be read");
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(path + " is not valid JSON: " + e.what());
  }
  if (!root.IsMap()) {
    throw std::runtime_error(path + " is not a JSON object");
  }
  std::vector<SummaryLeaf> out;
  append_leaves(out, root, "");
  return out;
}

std::string summary_table(const std::string& out_dir) {
  const std::string path = out_dir + "/summary.json";
  if (!std::ifstream(path)) {
    return "(no summary.json in " + out_dir + ": the scenario has no evaluator)\n";
  }
  std::vector<SummaryLeaf> leaves;
  try {
    leaves = summary_leaves(path);
  } catch (const std::runtime_error& e) {
    return std::string("(") + e.what() + ")\n";
  }
  std::string out = "\nsummary (" + path + ")\n";
  for (const SummaryLeaf& leaf : leaves) {
    const std::string& key = leaf.path;
    out += "  " + key + std::string(key.size() < 48 ? 48 - key.size() : 0, ' ') + " " + leaf.json + "\n";
  }
  return out;
}

}  // namespace robodds
