#include "common/number_parse.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace robodds {

std::optional<std::uint64_t> parse_whole_number(const std::string& text, std::uint64_t max) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  errno = 0;
  const unsigned long long value = std::strtoull(text.c_str(), nullptr, 10);
  if (errno == ERANGE || value > max) {
    return std::nullopt;
  }
  return static_cast<std::uint64_t>(value);
}

std::optional<double> parse_finite_number(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

}  // namespace robodds
