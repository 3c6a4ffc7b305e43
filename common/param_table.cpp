#include "common/param_table.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

#include "common/number_text.hpp"
#include "common/param_checks.hpp"

namespace robodds::params {
namespace {

bool is_plain_scalar(const std::string& text) {
  if (text.empty() || !(std::isalpha(static_cast<unsigned char>(text[0])) || text[0] == '_')) {
    return false;
  }
  for (const char c : text) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '/' || c == '.' || c == '-')) {
      return false;
    }
  }
  std::string lower;
  for (const char c : text) {
    lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  for (const char* reserved : {"true", "false", "yes", "no", "on", "off", "null", "y", "n"}) {
    if (lower == reserved) {
      return false;
    }
  }
  return true;
}

template <class T>
std::string list_text(const std::vector<T>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    out += (i == 0 ? "" : ", ") + yaml_text(values[i]);
  }
  return out + "]";
}

}  // namespace

const char* type_name(ParamKind kind) {
  switch (kind) {
    case ParamKind::kDouble:
      return "double";
    case ParamKind::kInt:
      return "int";
    case ParamKind::kUint:
      return "uint";
    case ParamKind::kBool:
      return "bool";
    case ParamKind::kString:
      return "string";
    case ParamKind::kEnum:
      return "enum";
    case ParamKind::kDoubleList:
      return "list of double";
    case ParamKind::kStringList:
      return "list of string";
    case ParamKind::kPointList:
      return "list of [x, y]";
  }
  return "?";
}

Check<double> finite() { return {"finite", [](std::string_view key, double v) { param_checks::require_finite(key, v); }}; }

Check<double> positive() {
  return {"> 0", [](std::string_view key, double v) { param_checks::require_positive(key, v); }};
}

Check<double> non_negative(std::string meaning_of_zero) {
  std::string text = meaning_of_zero.empty() ? ">= 0" : ">= 0 (" + meaning_of_zero + ")";
  return {std::move(text), [meaning_of_zero](std::string_view key, double v) {
            param_checks::require_non_negative(key, v, meaning_of_zero);
          }};
}

Check<double> in_open_interval(double low, double high) {
  return {"(" + shortest_text(low) + ", " + shortest_text(high) + ")", [low, high](std::string_view key, double v) {
            param_checks::require_in_open_interval(key, v, low, high);
          }};
}

Check<double> in_half_open_interval(double low, double high) {
  const std::string text = "[" + shortest_text(low) + ", " + shortest_text(high) + ")";
  return {text, [low, high, text](std::string_view key, double v) {
            if (!(v >= low && v < high)) {
              throw std::invalid_argument(std::string(key) + ": must be in " + text + " (got " + shortest_text(v) + ")");
            }
          }};
}

Check<long long> at_least(long long minimum) {
  return {">= " + std::to_string(minimum),
          [minimum](std::string_view key, long long v) { param_checks::require_at_least(key, v, minimum); }};
}

std::string yaml_text(double value) {
  if (std::isnan(value)) {
    return ".nan";
  }
  if (std::isinf(value)) {
    return value > 0 ? ".inf" : "-.inf";
  }
  // Fixed notation when it is short ("0.0005" rather than "5e-04"), else the shortest text;
  // both read back as the same double.
  char buffer[32];
  const std::to_chars_result fixed = std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::fixed);
  if (fixed.ec == std::errc() && fixed.ptr - buffer <= 12) {
    return std::string(buffer, fixed.ptr);
  }
  return shortest_text(value);
}

std::string yaml_text(long long value) { return std::to_string(value); }

std::string yaml_text(unsigned long long value) { return std::to_string(value); }

std::string yaml_text(bool value) { return value ? "true" : "false"; }

std::string yaml_text(const std::string& value) {
  if (is_plain_scalar(value)) {
    return value;
  }
  std::string out = "\"";
  for (const char c : value) {
    if (c == '"' || c == '\\') {
      out += '\\';
    }
    out += c;
  }
  return out + "\"";
}

std::string yaml_text(const std::vector<double>& values) { return list_text(values); }

std::string yaml_text(const std::vector<std::string>& values) { return list_text(values); }

std::string yaml_text(const std::vector<Point2>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    out += (i == 0 ? "[" : ", [") + yaml_text(values[i][0]) + ", " + yaml_text(values[i][1]) + "]";
  }
  return out + "]";
}

}  // namespace robodds::params
