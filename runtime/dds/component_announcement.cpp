#include "runtime/dds/component_announcement.hpp"

#include <cstring>

namespace robodds {
namespace {
constexpr const char* kPrefix = "robodds-components:";
}  // namespace

std::vector<std::uint8_t> component_announcement(const std::vector<std::string>& components) {
  std::string text = kPrefix;
  for (std::size_t i = 0; i < components.size(); ++i) {
    text += (i == 0 ? "" : ",") + components[i];
  }
  return std::vector<std::uint8_t>(text.begin(), text.end());
}

std::optional<std::vector<std::string>> announced_components(const std::vector<std::uint8_t>& user_data) {
  const std::string text(user_data.begin(), user_data.end());
  const std::size_t prefix = std::strlen(kPrefix);
  if (text.compare(0, prefix, kPrefix) != 0) {
    return std::nullopt;
  }
  std::vector<std::string> components;
  std::size_t begin = prefix;
  while (begin < text.size()) {
    const std::size_t comma = text.find(',', begin);
    const std::size_t end = comma == std::string::npos ? text.size() : comma;
    if (end > begin) {
      components.push_back(text.substr(begin, end - begin));
    }
    begin = end + 1;
  }
  return components;
}

}  // namespace robodds
