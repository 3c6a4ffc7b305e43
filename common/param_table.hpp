#pragma once
// The one source of a parameter struct's keys: each entry names the YAML key, the struct
// member, the unit, the range check and a one-line description. The default is the member's
// initialiser in the struct (written once, and what a default-constructed struct in a unit test
// gets); the table reads it from `S{}`. From a table come:
//   - the range checks of the struct's validate() (check_ranges; cross-field rules stay in
//     validate()),
//   - the runtime's reading of a component's parameters (runtime/config/param_table_reader.hpp): the
//     key set, the types and the built-in defaults,
//   - the documentation: `robodds components --params NAME` and the generated
//     config/<name>.params.yaml (doc(), common/param_doc.hpp), which a unit test compares with
//     the checked-in file.
// Pure: std only. Range failures throw std::invalid_argument("key: requirement (got value)")
// through common/param_checks.hpp.

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "common/param_doc.hpp"

namespace robodds::params {

using Point2 = std::array<double, 2>;  // [x, y], e.g. a way-point in m

enum class ParamKind { kDouble, kInt, kUint, kBool, kString, kEnum, kDoubleList, kStringList, kPointList };

/// "double", "int", ... as printed in the documentation.
const char* type_name(ParamKind kind);

/// A value as read from YAML, by kind: kInt -> int64, kUint -> uint64, kEnum -> its name.
using ParamValue = std::variant<double, std::int64_t, std::uint64_t, bool, std::string, std::vector<double>,
                                std::vector<std::string>, std::vector<Point2>>;

/// A named range check: `text` is what the documentation prints, `apply(key, value)` throws
/// std::invalid_argument("key: requirement (got value)"). An empty check accepts everything.
template <class T>
struct Check {
  std::string text;
  std::function<void(std::string_view key, const T& value)> apply;
};

/// The value type the checks of a field of type T see: integers as long long.
template <class T>
using CheckValue = std::conditional_t<std::is_integral_v<T> && !std::is_same_v<T, bool>, long long, T>;

Check<double> finite();
/// > 0 and finite.
Check<double> positive();
/// >= 0 and finite; `meaning_of_zero` (e.g. "0 = no limit") is printed and put in the message.
Check<double> non_negative(std::string meaning_of_zero = {});
/// In (low, high), finite.
Check<double> in_open_interval(double low, double high);
/// In [low, high), finite: e.g. a probability that must leave some samples through, [0, 1).
Check<double> in_half_open_interval(double low, double high);
/// An integer >= minimum.
Check<long long> at_least(long long minimum);
/// `check` printed as `text`, for a range that a cross-field rule of validate() completes, e.g.
/// shown_as(positive(), "(0, num_particles]").
template <class T>
Check<T> shown_as(Check<T> check, std::string text) {
  check.text = std::move(text);
  return check;
}
/// No range (integers, flags, lists).
template <class T>
Check<T> any() {
  return {};
}

// Text of values as flow YAML; doubles as the shortest text that reads back exactly, in fixed
// notation when that is short (common/number_text.hpp otherwise).
std::string yaml_text(double value);
std::string yaml_text(long long value);
std::string yaml_text(unsigned long long value);
std::string yaml_text(bool value);
std::string yaml_text(const std::string& value);
std::string yaml_text(const std::vector<double>& values);
std::string yaml_text(const std::vector<std::string>& values);
std::string yaml_text(const std::vector<Point2>& values);

namespace detail {

template <class T>
constexpr ParamKind kind_of() {
  if constexpr (std::is_same_v<T, double>) {
    return ParamKind::kDouble;
  } else if constexpr (std::is_same_v<T, bool>) {
    return ParamKind::kBool;
  } else if constexpr (std::is_integral_v<T> && std::is_signed_v<T>) {
    return ParamKind::kInt;
  } else if constexpr (std::is_integral_v<T>) {
    return ParamKind::kUint;
  } else if constexpr (std::is_same_v<T, std::string>) {
    return ParamKind::kString;
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    return ParamKind::kDoubleList;
  } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
    return ParamKind::kStringList;
  } else {
    static_assert(std::is_same_v<T, std::vector<Point2>>, "unsupported parameter type");
    return ParamKind::kPointList;
  }
}

template <class T>
std::string text_of(const T& value) {
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool> && std::is_signed_v<T>) {
    return yaml_text(static_cast<long long>(value));
  } else if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    return yaml_text(static_cast<unsigned long long>(value));
  } else {
    return yaml_text(value);
  }
}

/// The field's value from a ParamValue of its kind; integers must fit the field's type.
template <class T>
T from_value(std::string_view key, const ParamValue& value) {
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    using Wide = std::conditional_t<std::is_signed_v<T>, std::int64_t, std::uint64_t>;
    const Wide wide = std::get<Wide>(value);
    if (wide < static_cast<Wide>(std::numeric_limits<T>::min()) || wide > static_cast<Wide>(std::numeric_limits<T>::max())) {
      throw std::invalid_argument(std::string(key) + ": out of range for " + type_name(kind_of<T>()) + " (got " +
                                  text_of(wide) + ")");
    }
    return static_cast<T>(wide);
  } else {
    return std::get<T>(value);
  }
}

}  // namespace detail

/// One parameter of struct S, type-erased over the member's type.
template <class S>
struct TableEntry {
  ParamKind kind;
  ParamInfo info;  // without default_yaml (doc() fills it from S{})
  std::function<std::string(const S&)> text;                  // the field's value as flow YAML
  std::function<void(S&, const ParamValue&)> set;            // throws "key: ..." (enum names, int range)
  std::function<void(const S&)> check;                       // the range check, throws "key: ..."
};

template <class S>
class ParamTable {
 public:
  explicit ParamTable(std::string summary = {}) : summary_(std::move(summary)) {}

  /// A member of S.
  template <class T>
  ParamTable& add(std::string key, T S::*member, std::string unit, Check<CheckValue<T>> check, std::string description) {
    return add_field<T>(std::move(key), [member](S& s) -> T& { return s.*member; },
                        [member](const S& s) -> const T& { return s.*member; }, std::move(unit), std::move(check),
                        std::move(description));
  }

  /// A member of a member of S (e.g. the limits of a plant, the gains of a controller).
  template <class M, class T>
  ParamTable& add(std::string key, M S::*outer, T M::*member, std::string unit, Check<CheckValue<T>> check,
                  std::string description) {
    return add_field<T>(std::move(key), [outer, member](S& s) -> T& { return (s.*outer).*member; },
                        [outer, member](const S& s) -> const T& { return (s.*outer).*member; }, std::move(unit),
                        std::move(check), std::move(description));
  }

  /// An enum member, written in YAML by name: `parse` throws std::invalid_argument("key: ...")
  /// for an unknown name, `name_of` gives the name of a value; `names` are all the names.
  template <class E>
  ParamTable& add_enum(std::string key, E S::*member, E (*parse)(std::string_view), std::string (*name_of)(E),
                       const std::vector<std::string>& names, std::string description) {
    std::string range;
    for (const std::string& name : names) {
      range += (range.empty() ? "" : " | ") + name;
    }
    TableEntry<S> entry{ParamKind::kEnum, ParamInfo{key, type_name(ParamKind::kEnum), "", "", range, std::move(description)},
                        [member, name_of](const S& s) { return yaml_text(name_of(s.*member)); },
                        [member, parse](S& s, const ParamValue& value) { s.*member = parse(std::get<std::string>(value)); },
                        [](const S&) {}};
    entries_.push_back(std::move(entry));
    return *this;
  }

  /// Every entry of `inner`, for the member `member` of S (same keys): a node's parameters
  /// that contain the algorithm's struct.
  template <class M>
  ParamTable& include(M S::*member, const ParamTable<M>& inner) {
    for (const TableEntry<M>& e : inner.entries()) {
      entries_.push_back(TableEntry<S>{e.kind, e.info, [member, text = e.text](const S& s) { return text(s.*member); },
                                       [member, set = e.set](S& s, const ParamValue& v) { set(s.*member, v); },
                                       [member, check = e.check](const S& s) { check(s.*member); }});
    }
    for (const ParamGroup& group : inner.groups()) {
      groups_.push_back(group);
    }
    return *this;
  }

  /// Every entry of `inner` under the nested map `prefix` (keys "prefix.key"), for the member
  /// `member` of S: a node that holds two algorithms' structs side by side (the range-rate
  /// observer node: "sta.b", "linear.k1"). `description` is the map's comment.
  template <class M>
  ParamTable& include_as(const std::string& prefix, M S::*member, const ParamTable<M>& inner, std::string description) {
    groups_.push_back(ParamGroup{prefix, std::move(description)});
    for (const TableEntry<M>& e : inner.entries()) {
      ParamInfo info = e.info;
      info.key = prefix + "." + info.key;
      entries_.push_back(TableEntry<S>{e.kind, std::move(info), [member, text = e.text](const S& s) { return text(s.*member); },
                                       [member, set = e.set](S& s, const ParamValue& v) { set(s.*member, v); },
                                       [member, prefix, check = e.check](const S& s) {
                                         try {
                                           check(s.*member);
                                         } catch (const std::invalid_argument& error) {
                                           // The inner check names its own key: put the prefix in front.
                                           throw std::invalid_argument(prefix + "." + error.what());
                                         }
                                       }});
    }
    return *this;
  }

  /// The comment of a map of nested keys, e.g. group("forward_gains", "used while ...").
  ParamTable& group(std::string prefix, std::string description) {
    groups_.push_back(ParamGroup{std::move(prefix), std::move(description)});
    return *this;
  }

  const std::vector<TableEntry<S>>& entries() const { return entries_; }
  const std::vector<ParamGroup>& groups() const { return groups_; }

  /// Runs every entry's range check in table order; throws at the first failure.
  void check_ranges(const S& s) const {
    for (const TableEntry<S>& e : entries_) {
      e.check(s);
    }
  }

  /// The documentation, with the defaults of `defaults` (normally S{}).
  ParamDoc doc(const S& defaults = S{}) const {
    ParamDoc out{summary_, groups_, {}};
    for (const TableEntry<S>& e : entries_) {
      ParamInfo info = e.info;
      info.default_yaml = e.text(defaults);
      out.params.push_back(std::move(info));
    }
    return out;
  }

 private:
  template <class T>
  ParamTable& add_field(std::string key, std::function<T&(S&)> ref, std::function<const T&(const S&)> get,
                        std::string unit, Check<CheckValue<T>> check, std::string description) {
    constexpr ParamKind kind = detail::kind_of<T>();
    TableEntry<S> entry{kind, ParamInfo{key, type_name(kind), "", std::move(unit), check.text, std::move(description)},
                        [get](const S& s) { return detail::text_of(get(s)); },
                        [ref, key](S& s, const ParamValue& value) { ref(s) = detail::from_value<T>(key, value); },
                        [get, key, apply = check.apply](const S& s) {
                          if (apply) {
                            apply(key, static_cast<CheckValue<T>>(get(s)));
                          }
                        }};
    entries_.push_back(std::move(entry));
    return *this;
  }

  std::string summary_;
  std::vector<ParamGroup> groups_;
  std::vector<TableEntry<S>> entries_;
};

}  // namespace robodds::params
