#pragma once
// Text forms of IDL samples, built on the generated visit_fields(): CSV rows for the evaluator
// (exact: the shortest round-trip text of each double, so outputs can be compared byte for byte) and
// readable "field: value" text for `robodds echo`.

#include <charconv>
#include <cstdint>
#include <string>
#include <type_traits>

#include "common/number_text.hpp"
#include "runtime/io/sample_fields.hpp"

namespace robodds {

namespace detail {

// Shortest text that parses back to the same double (exact, and ~10x cheaper than %.17g, which
// dominated the co-located lockstep profile when every sample is recorded).
inline void append_scalar(std::string& out, double value) { append_shortest(out, value); }

// Decimal text of an integer, as std::to_string spells it, without a temporary string (every
// CSV row has several: the evaluator's recording was a tenth of the co-located paper-2 profile).
template <class I>
void append_integer(std::string& out, I value) {
  char buffer[24];
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

template <class V>
void append_value(std::string& out, const V& value);

}  // namespace detail

/// Appends a time in ns as seconds with 9 decimals ("12.340000000"), exactly, with integer
/// arithmetic (no rounding through double). Negative times get a leading '-'.
inline void append_seconds(std::string& out, std::int64_t ns) {
  const std::uint64_t magnitude = ns < 0 ? 0 - static_cast<std::uint64_t>(ns) : static_cast<std::uint64_t>(ns);
  if (ns < 0) {
    out += '-';
  }
  detail::append_integer(out, magnitude / 1000000000ULL);
  char fraction[10] = {'.', '0', '0', '0', '0', '0', '0', '0', '0', '0'};
  std::uint64_t rest = magnitude % 1000000000ULL;
  for (int i = 9; i > 0 && rest != 0; --i, rest /= 10) {
    fraction[i] = static_cast<char>('0' + rest % 10);
  }
  out.append(fraction, sizeof(fraction));
}

namespace detail {

template <class S>
void append_struct(std::string& out, const S& value) {
  bool first = true;
  idl::visit_fields(value, [&](const char*, const auto& field) {
    if (!first) {
      out += ':';
    }
    first = false;
    append_value(out, field);
  });
}

template <class V>
void append_value(std::string& out, const V& value) {
  if constexpr (std::is_same_v<V, bool>) {
    out += value ? "1" : "0";
  } else if constexpr (std::is_floating_point_v<V>) {
    append_scalar(out, static_cast<double>(value));
  } else if constexpr (std::is_enum_v<V>) {
    append_integer(out, static_cast<long long>(value));
  } else if constexpr (std::is_integral_v<V>) {
    append_integer(out, value);
  } else if constexpr (std::is_same_v<V, std::string>) {
    out += value;
  } else if constexpr (IsVector<V>::value) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      if (i != 0) {
        out += ';';
      }
      if constexpr (std::is_class_v<std::decay_t<decltype(value[i])>>) {
        append_struct(out, value[i]);
      } else {
        append_value(out, value[i]);
      }
    }
  } else {
    out += value.to_string();  // fixed_string<N>
  }
}

}  // namespace detail

/// Comma-separated field names of a sample type (nested fields dotted, arrays as name[i]).
template <class Msg>
std::string csv_header() {
  std::string out;
  idl::visit_fields(Msg{}, [&](const char* name, const auto&) {
    out += out.empty() ? "" : ",";
    out += name;
  });
  return out;
}

/// One CSV row (no newline). Sequences are ';'-separated, struct elements ':'-separated.
template <class Msg>
void append_csv_row(std::string& out, const Msg& sample) {
  bool first = true;
  idl::visit_fields(sample, [&](const char*, const auto& value) {
    if (!first) {
      out += ',';
    }
    first = false;
    detail::append_value(out, value);
  });
}

/// "name: value" lines, for people.
template <class Msg>
std::string to_text(const Msg& sample) {
  std::string out;
  idl::visit_fields(sample, [&](const char* name, const auto& value) {
    out += "  ";
    out += name;
    out += ": ";
    detail::append_value(out, value);
    out += '\n';
  });
  return out;
}

}  // namespace robodds
