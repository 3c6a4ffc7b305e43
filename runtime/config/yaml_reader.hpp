#pragma once
// Reading a YAML document whose every error names its file and the key: ConfigError
// "<file>: <key>: <reason>". The scenario loader reads with it, and so does the layer above for
// the sections it registered (system/mission_plan.cpp).

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/did_you_mean.hpp"
#include "runtime/base/error.hpp"

namespace robodds {

class YamlReader {
 public:
  explicit YamlReader(std::string file) : file_(std::move(file)) {}

  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const std::string& key, const std::string& reason) const {
    throw ConfigError(located(file_, key, reason));
  }

  /// The scalar at `key` as T; "missing" or "expected <expected>, got '<text>'" otherwise.
  template <class T>
  T scalar(const YAML::Node& node, const std::string& key, const char* expected) const {
    if (!node || !node.IsScalar()) {
      fail(key, node ? std::string("expected ") + expected : "missing");
    }
    try {
      return node.as<T>();
    } catch (const YAML::Exception&) {
      fail(key, std::string("expected ") + expected + ", got '" + node.Scalar() + "'");
    }
  }

  /// A finite number.
  double finite(const YAML::Node& node, const std::string& key) const {
    const double value = scalar<double>(node, key, "a number");
    if (!std::isfinite(value)) {
      fail(key, "must be finite");
    }
    return value;
  }

  /// Refuses keys of a map entry other than `known` (`list`: the same, comma-separated, for the message).
  void only_keys(const YAML::Node& node, const std::string& key, const std::set<std::string>& known, const char* list) const {
    for (const auto& item : node) {
      const std::string k = item.first.as<std::string>();
      if (known.count(k) == 0) {
        fail(key + "." + k, "unknown key" + did_you_mean(k, std::vector<std::string>(known.begin(), known.end())) + " (known: " + list + ")");
      }
    }
  }

 private:
  std::string file_;
};

}  // namespace robodds
