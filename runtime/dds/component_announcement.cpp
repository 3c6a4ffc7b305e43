#include "runtime/dds/component_announcement.hpp"

#include <cctype>
#include <limits>

#include "common/number_parse.hpp"

namespace robodds {
namespace {
constexpr const char* kPrefix = "robodds-components:";
constexpr const char* kRunPrefix = "robodds-run:";
constexpr const char* kDigestPrefix = "robodds-digest:";

bool hex_char(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0 || (c >= 'a' && c <= 'f'); }

bool starts_with(const std::string& text, const char* prefix) { return text.rfind(prefix, 0) == 0; }

/// "a=<hex>;b=<hex>" into `out`; false when malformed (empty or bad label, bad hex, duplicates, too many).
bool parse_digest(const std::string& text, std::map<std::string, std::string>& out) {
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t semi = text.find(';', begin);
    const std::size_t end = semi == std::string::npos ? text.size() : semi;
    const std::string item = text.substr(begin, end - begin);
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == item.size() || item.size() - eq - 1 > 128) {
      return false;
    }
    const std::string label = item.substr(0, eq);
    const std::string hex = item.substr(eq + 1);
    for (char c : label) {
      if (!digest_label_char(c)) {
        return false;
      }
    }
    for (char c : hex) {
      if (!hex_char(c)) {
        return false;
      }
    }
    if (!out.emplace(label, hex).second || out.size() > kMaxDigestEntries) {
      return false;
    }
    if (semi == std::string::npos) {
      break;
    }
    begin = semi + 1;
  }
  return true;
}

}  // namespace

std::vector<std::uint8_t> component_announcement(const std::vector<std::string>& components, std::optional<std::uint64_t> run_id,
                                                 const RunDigest& digest) {
  std::string text = kPrefix;
  for (std::size_t i = 0; i < components.size(); ++i) {
    text += (i == 0 ? "" : ",") + components[i];
  }
  if (run_id) {
    text += std::string("\n") + kRunPrefix + std::to_string(*run_id);
    if (!digest.empty()) {
      text += std::string("\n") + kDigestPrefix;
      for (std::size_t i = 0; i < digest.size(); ++i) {
        text += (i == 0 ? "" : ";") + sanitised_digest_label(digest[i].label) + "=" + digest[i].digest;
      }
    }
  }
  return std::vector<std::uint8_t>(text.begin(), text.end());
}

std::optional<Announcement> parse_announcement(const std::vector<std::uint8_t>& user_data) {
  if (user_data.size() > kMaxAnnouncementBytes) {
    return std::nullopt;
  }
  const std::string text(user_data.begin(), user_data.end());
  if (!starts_with(text, kPrefix) || text.find('\0') != std::string::npos) {
    return std::nullopt;
  }
  std::vector<std::string> lines;
  std::size_t begin = 0;
  while (true) {
    const std::size_t newline = text.find('\n', begin);
    lines.push_back(text.substr(begin, newline == std::string::npos ? std::string::npos : newline - begin));
    if (newline == std::string::npos) {
      break;
    }
    begin = newline + 1;
  }
  if (lines.size() > 3) {
    return std::nullopt;
  }
  Announcement a;
  const std::string& names = lines[0];
  begin = std::char_traits<char>::length(kPrefix);
  while (begin < names.size()) {
    const std::size_t comma = names.find(',', begin);
    const std::size_t end = comma == std::string::npos ? names.size() : comma;
    if (end > begin) {
      a.components.push_back(names.substr(begin, end - begin));
    }
    begin = end + 1;
  }
  if (lines.size() >= 2) {
    if (!starts_with(lines[1], kRunPrefix)) {
      return std::nullopt;
    }
    const std::optional<std::uint64_t> id =
        parse_whole_number(lines[1].substr(std::char_traits<char>::length(kRunPrefix)), std::numeric_limits<std::uint64_t>::max());
    if (!id) {
      return std::nullopt;
    }
    a.run_id = *id;
  }
  if (lines.size() == 3) {
    if (!starts_with(lines[2], kDigestPrefix) ||
        !parse_digest(lines[2].substr(std::char_traits<char>::length(kDigestPrefix)), a.digest)) {
      return std::nullopt;
    }
  }
  return a;
}

std::optional<std::vector<std::string>> announced_components(const std::vector<std::uint8_t>& user_data) {
  std::optional<Announcement> a = parse_announcement(user_data);
  if (!a) {
    return std::nullopt;
  }
  return std::move(a->components);
}

}  // namespace robodds
