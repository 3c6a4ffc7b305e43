#include "runtime/config/params.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <sstream>

#include "common/did_you_mean.hpp"
#include "runtime/base/error.hpp"

namespace robodds {
namespace {

void flatten(const YAML::Node& node, const std::string& prefix, const std::string& file, FlatParams& out) {
  for (const auto& item : node) {
    const std::string key = prefix + item.first.as<std::string>();
    const YAML::Node& value = item.second;
    if (value.IsMap()) {
      flatten(value, key + ".", file, out);
    } else {
      YAML::Emitter emitter;
      emitter << YAML::Flow << value;
      out[key] = ParamEntry{emitter.c_str(), file};
    }
  }
}

std::string known_keys(const FlatParams& params) {
  std::string keys;
  for (const auto& [key, entry] : params) {
    keys += (keys.empty() ? "" : ", ") + key;
  }
  return keys;
}

template <class T>
T convert(const ParamEntry& entry, const std::string& key, const char* expected) {
  try {
    YAML::Node node = YAML::Load(entry.yaml);
    if (!node.IsScalar()) {
      throw ConfigError(located(entry.file, key, std::string("expected ") + expected + ", got '" + entry.yaml + "'"));
    }
    return node.as<T>();
  } catch (const YAML::Exception&) {
    throw ConfigError(located(entry.file, key, std::string("expected ") + expected + ", got '" + entry.yaml + "'"));
  }
}

}  // namespace

FlatParams load_param_file(const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ConfigError(located(path, "", "cannot open parameter file"));
  } catch (const YAML::Exception& e) {
    throw ConfigError(located(path, "", "invalid YAML at line " + std::to_string(e.mark.line + 1) + ": " + e.msg));
  }
  FlatParams out;
  if (root.IsNull()) {
    return out;
  }
  if (!root.IsMap()) {
    throw ConfigError(located(path, "", "expected a map of parameters"));
  }
  flatten(root, "", path, out);
  return out;
}

std::optional<std::pair<std::string, std::string>> split_param_assignment(const std::string& text) {
  const std::size_t equals = text.find('=');
  if (equals == std::string::npos) {
    return std::nullopt;
  }
  std::string key = text.substr(0, equals);
  const std::size_t dot = key.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == key.size()) {
    return std::nullopt;
  }
  return std::make_pair(std::move(key), text.substr(equals + 1));
}

FlatParams parse_param_assignments(const std::vector<std::string>& assignments) {
  FlatParams out;
  for (const std::string& assignment : assignments) {
    const auto split = split_param_assignment(assignment);
    if (!split || split->second.empty()) {
      throw ConfigError("--set '" + assignment + "': expected component.parameter=value (e.g. controller.epsilon_m=0.1)");
    }
    const auto& [key, value] = *split;
    if (!out.emplace(key, ParamEntry{value, "--set"}).second) {
      throw ConfigError("--set '" + assignment + "': " + key + " is set twice");
    }
  }
  return out;
}

FlatParams merge_params(const FlatParams& defaults, const FlatParams& overrides) {
  FlatParams merged = defaults;
  for (const auto& [key, entry] : overrides) {
    if (defaults.count(key) == 0) {
      const std::string known = known_keys(defaults);
      throw ConfigError(located(entry.file, key, "unknown parameter" + did_you_mean(key, listed_names(known)) + " (known: " + known + ")"));
    }
    merged[key] = entry;
  }
  return merged;
}

ParamReader::ParamReader(std::string owner, FlatParams params) : owner_(std::move(owner)), params_(std::move(params)) {}

const ParamEntry& ParamReader::entry(const std::string& key) {
  auto it = params_.find(key);
  if (it == params_.end()) {
    std::string file = params_.empty() ? owner_ : params_.begin()->second.file;
    throw ConfigError(located(file, key, "missing parameter"));
  }
  read_.insert(key);
  return it->second;
}

bool ParamReader::has(const std::string& key) const { return params_.count(key) != 0; }

double ParamReader::get_double(const std::string& key) {
  const ParamEntry& e = entry(key);
  const double value = convert<double>(e, key, "a number");
  if (!std::isfinite(value)) {
    throw ConfigError(located(e.file, key, "must be finite (got " + e.yaml + ")"));
  }
  return value;
}

std::int64_t ParamReader::get_int(const std::string& key) {
  return convert<std::int64_t>(entry(key), key, "an integer");
}

std::uint64_t ParamReader::get_uint(const std::string& key) {
  const ParamEntry& e = entry(key);
  if (!e.yaml.empty() && e.yaml[0] == '-') {
    throw ConfigError(located(e.file, key, "expected a non-negative integer, got '" + e.yaml + "'"));
  }
  return convert<std::uint64_t>(e, key, "a non-negative integer");
}

bool ParamReader::get_bool(const std::string& key) { return convert<bool>(entry(key), key, "true or false"); }

std::string ParamReader::get_string(const std::string& key) { return convert<std::string>(entry(key), key, "a string"); }

std::vector<double> ParamReader::get_double_list(const std::string& key) {
  const ParamEntry& e = entry(key);
  try {
    YAML::Node node = YAML::Load(e.yaml);
    if (!node.IsSequence()) {
      throw ConfigError(located(e.file, key, "expected a list of numbers, got '" + e.yaml + "'"));
    }
    std::vector<double> out;
    for (const auto& item : node) {
      const double value = item.as<double>();
      if (!std::isfinite(value)) {
        throw ConfigError(located(e.file, key, "element " + std::to_string(out.size()) + " is not finite"));
      }
      out.push_back(value);
    }
    return out;
  } catch (const YAML::Exception&) {
    throw ConfigError(located(e.file, key, "expected a list of numbers, got '" + e.yaml + "'"));
  }
}

std::vector<std::string> ParamReader::get_string_list(const std::string& key) {
  const ParamEntry& e = entry(key);
  try {
    YAML::Node node = YAML::Load(e.yaml);
    if (!node.IsSequence()) {
      throw ConfigError(located(e.file, key, "expected a list of strings, got '" + e.yaml + "'"));
    }
    std::vector<std::string> out;
    for (const auto& item : node) {
      out.push_back(item.as<std::string>());
    }
    return out;
  } catch (const YAML::Exception&) {
    throw ConfigError(located(e.file, key, "expected a list of strings, got '" + e.yaml + "'"));
  }
}

std::vector<std::array<double, 2>> ParamReader::get_point_list(const std::string& key) {
  const ParamEntry& e = entry(key);
  const std::string expected = "expected a list of [x, y] pairs, got '" + e.yaml + "'";
  try {
    YAML::Node node = YAML::Load(e.yaml);
    if (!node.IsSequence()) {
      throw ConfigError(located(e.file, key, expected));
    }
    std::vector<std::array<double, 2>> out;
    for (const auto& item : node) {
      if (!item.IsSequence() || item.size() != 2) {
        throw ConfigError(located(e.file, key, "element " + std::to_string(out.size()) + " is not an [x, y] pair"));
      }
      const std::array<double, 2> point{item[0].as<double>(), item[1].as<double>()};
      if (!std::isfinite(point[0]) || !std::isfinite(point[1])) {
        throw ConfigError(located(e.file, key, "element " + std::to_string(out.size()) + " is not finite"));
      }
      out.push_back(point);
    }
    return out;
  } catch (const YAML::Exception&) {
    throw ConfigError(located(e.file, key, expected));
  }
}

void ParamReader::fail(const std::string& message) const {
  // validate() messages start with the key: find which file that key came from.
  const std::string key = message.substr(0, message.find(':'));
  auto it = params_.find(key);
  if (it == params_.end()) {
    it = params_.lower_bound(key + ".");  // a group of keys, e.g. "forward_gains" for forward_gains.kd
    if (it != params_.end() && it->first.rfind(key + ".", 0) != 0) {
      it = params_.end();
    }
  }
  const std::string file = it != params_.end() ? it->second.file : owner_;
  throw ConfigError(located(file, "", message));
}

void ParamReader::check_all_read() const {
  for (const auto& [key, entry] : params_) {
    if (read_.count(key) == 0) {
      throw ConfigError(located(entry.file, key, "unknown parameter for " + owner_ + " (never read)"));
    }
  }
}

}  // namespace robodds
