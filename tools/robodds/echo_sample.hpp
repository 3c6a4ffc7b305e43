#pragma once
// An IDL sample as the named values `robodds echo` prints (echo_format.hpp), through the
// generated field visitors: enums by their IDL name, booleans as true/false, sequences as lists
// (struct elements as records), numbers as the shortest text that reads back the same.

#include <cmath>
#include <string>
#include <type_traits>
#include <utility>

#include "common/number_text.hpp"
#include "robodds/idl/robodds_enums.hpp"
#include "runtime/io/sample_fields.hpp"
#include "tools/robodds/echo_format.hpp"

namespace robodds {

namespace detail {
template <class T, class = void>
struct HasToString : std::false_type {};
template <class T>
struct HasToString<T, std::void_t<decltype(std::declval<const T&>().to_string())>> : std::true_type {};
}  // namespace detail

template <class V>
EchoValue echo_value(const V& value);

/// The leaf fields of a sample (or of a struct element of a sequence), in IDL order.
template <class S>
EchoFields echo_fields(const S& sample) {
  EchoFields fields;
  idl::visit_fields(sample, [&fields](const char* name, const auto& value) { fields.emplace_back(name, echo_value(value)); });
  return fields;
}

template <class V>
EchoValue echo_value(const V& value) {
  EchoValue out;
  if constexpr (std::is_same_v<V, bool>) {
    out.kind = EchoValue::Kind::boolean;
    out.text = value ? "true" : "false";
  } else if constexpr (std::is_floating_point_v<V>) {
    out.text = shortest_text(static_cast<double>(value));
    out.finite = std::isfinite(value);
  } else if constexpr (std::is_enum_v<V>) {
    // A number the IDL does not name (any writer may send one) stays a number.
    const char* name = idl::enum_name(value);
    out.kind = name != nullptr ? EchoValue::Kind::text : EchoValue::Kind::number;
    out.text = name != nullptr ? name : std::to_string(static_cast<long long>(value));
  } else if constexpr (std::is_integral_v<V>) {
    out.text = std::to_string(value);
  } else if constexpr (std::is_same_v<V, std::string>) {
    out.kind = EchoValue::Kind::text;
    out.text = value;
  } else if constexpr (detail::IsVector<V>::value) {
    out.kind = EchoValue::Kind::list;
    for (const auto& element : value) {
      out.items.push_back(echo_value(element));
    }
  } else if constexpr (detail::HasToString<V>::value) {
    out.kind = EchoValue::Kind::text;  // fixed_string<N>
    out.text = value.to_string();
  } else {
    out.kind = EchoValue::Kind::record;  // a struct element of a sequence
    out.fields = echo_fields(value);
  }
  return out;
}

}  // namespace robodds
