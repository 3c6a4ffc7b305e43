#pragma once
// Component parameters. Values come from the component's parameter table (its defaults,
// default_params() in runtime/config/param_table_reader.hpp) with scenario overrides on top. Every key
// remembers the file it came from, so each error names file, key and reason.
//
// A component reads every key once into its plain parameter struct (read_params(reader, table))
// and calls validate(); afterwards the runtime checks that every key was read.

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace robodds {

/// One parameter value: its YAML text (scalar or flow sequence) and the file it came from.
struct ParamEntry {
  std::string yaml;
  std::string file;
};

/// Flattened parameter tree: nested maps become dotted keys ("gains.kd"); sequences are leaves.
using FlatParams = std::map<std::string, ParamEntry>;

/// Reads a YAML file's top-level map into FlatParams (throws ConfigError naming the file).
FlatParams load_param_file(const std::string& path);

/// A `--set` text "component.parameter=value" split at its first '=' into {key, value}; nullopt
/// when it has no '=' or the key is not two non-empty parts around a '.'. The value may be empty
/// (parse_param_assignments refuses that; a sweep's grid splits it further).
std::optional<std::pair<std::string, std::string>> split_param_assignment(const std::string& text);

/// The command line's `--set component.parameter=value` assignments as FlatParams whose file is
/// "--set" (so later errors say "--set: controller.epsilon_m: ..."). The value is YAML text, e.g.
/// `0.1` or `[1, 2]`. ConfigError naming the assignment if it has no '=', no '.' in the key or an
/// empty part, or sets one key twice.
FlatParams parse_param_assignments(const std::vector<std::string>& assignments);

/// Applies overrides; an override of a key the defaults do not have is a ConfigError naming
/// the override's file, the key and the known keys.
FlatParams merge_params(const FlatParams& defaults, const FlatParams& overrides);

class ParamReader {
 public:
  ParamReader() = default;
  ParamReader(std::string owner, FlatParams params);

  double get_double(const std::string& key);
  std::int64_t get_int(const std::string& key);
  std::uint64_t get_uint(const std::string& key);
  bool get_bool(const std::string& key);
  std::string get_string(const std::string& key);
  std::vector<double> get_double_list(const std::string& key);
  std::vector<std::string> get_string_list(const std::string& key);
  /// A list of [x, y] pairs, e.g. way-points.
  std::vector<std::array<double, 2>> get_point_list(const std::string& key);
  bool has(const std::string& key) const;

  /// A string parameter turned into a value by `parse` (e.g. an enum from its name); a parse
  /// failure, whose message must start with "key: ", is reported through fail().
  template <class Parse>
  auto get_parsed(const std::string& key, Parse parse) -> decltype(parse(std::string{})) {
    const std::string text = get_string(key);
    try {
      return parse(text);
    } catch (const std::exception& e) {
      fail(e.what());
    }
  }

  /// Turns a validate() message "key: reason" into a ConfigError naming the key's file.
  [[noreturn]] void fail(const std::string& message) const;

  /// Runs a check that throws "key: reason" (e.g. one of common/param_checks.hpp) and reports a
  /// failure through fail().
  template <class Check>
  void check(Check&& check_values) const {
    try {
      check_values();
    } catch (const std::exception& e) {
      fail(e.what());
    }
  }

  /// Runs params.validate() and reports a failure through fail().
  template <class Params>
  void validate(const Params& params) const {
    check([&params] { params.validate(); });
  }

  /// Throws ConfigError if a key was never read (a typo or a stale key in a params file).
  void check_all_read() const;
  const std::string& owner() const { return owner_; }

 private:
  const ParamEntry& entry(const std::string& key);

  std::string owner_;
  FlatParams params_;
  std::set<std::string> read_;
};

}  // namespace robodds
