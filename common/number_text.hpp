#pragma once
// The project's one text form of a double: the shortest text that reads back as the same value
// ("0.1", "-2.5", "1e-09", "nan", "inf"). Exact, so CSV outputs compare byte for byte, and about
// 10x cheaper than "%.17g". Used for CSV rows and for the "(got ...)" of every error message.

#include <charconv>
#include <string>

namespace robodds {

inline void append_shortest(std::string& out, double value) {
  char buffer[32];
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

inline std::string shortest_text(double value) {
  std::string text;
  append_shortest(text, value);
  return text;
}

}  // namespace robodds
