#include "common/param_doc.hpp"

#include <algorithm>
#include <array>
#include <set>
#include <stdexcept>
#include <utility>

namespace robodds::params {
namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t end = text.find(separator); end != std::string::npos; end = text.find(separator, start)) {
    parts.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  parts.push_back(text.substr(start));
  return parts;
}

std::string join_prefix(const std::vector<std::string>& parts, std::size_t count) {
  std::string prefix;
  for (std::size_t i = 0; i < count; ++i) {
    prefix += (i == 0 ? "" : ".") + parts[i];
  }
  return prefix;
}

/// "unit, range: description", leaving out what is empty.
std::string comment_of(const ParamInfo& info) {
  std::string head = info.unit;
  if (!info.range.empty()) {
    head += (head.empty() ? "" : ", ") + info.range;
  }
  if (head.empty()) {
    return info.description;
  }
  return info.description.empty() ? head : head + ": " + info.description;
}

std::string group_comment(const ParamDoc& doc, const std::string& prefix) {
  for (const ParamGroup& group : doc.groups) {
    if (group.prefix == prefix) {
      return group.description;
    }
  }
  return "";
}

// Lines longer than this put their comment right after the value instead of widening the
// comment column of every line (e.g. a long way-point list).
constexpr std::size_t kMaxAlignedWidth = 40;

}  // namespace

std::string render_params_yaml(const ParamDoc& doc) {
  std::string out;
  if (!doc.summary.empty()) {
    for (const std::string& line : split(doc.summary, '\n')) {
      out += line.empty() ? "#\n" : "# " + line + "\n";
    }
  }
  out += std::string("# ") + kGeneratedNote + "\n";
  std::vector<std::pair<std::string, std::string>> lines;  // code, comment
  std::vector<std::string> open;                           // path of the nested maps now open
  std::set<std::string> closed;                            // maps already left
  for (const ParamInfo& info : doc.params) {
    const std::vector<std::string> parts = split(info.key, '.');
    const std::size_t depth = parts.size() - 1;
    std::size_t common = 0;
    while (common < open.size() && common < depth && open[common] == parts[common]) {
      ++common;
    }
    for (std::size_t level = open.size(); level > common; --level) {
      closed.insert(join_prefix(open, level));
    }
    open.resize(common);
    for (std::size_t level = common; level < depth; ++level) {
      const std::string prefix = join_prefix(parts, level + 1);
      if (closed.count(prefix) != 0) {
        throw std::invalid_argument(info.key + ": the keys of '" + prefix + "' must be next to each other in the table");
      }
      open.push_back(parts[level]);
      lines.emplace_back(std::string(2 * level, ' ') + parts[level] + ":", group_comment(doc, prefix));
    }
    lines.emplace_back(std::string(2 * depth, ' ') + parts.back() + ": " + info.default_yaml, comment_of(info));
  }
  std::size_t column = 0;
  for (const auto& [code, comment] : lines) {
    if (code.size() <= kMaxAlignedWidth) {
      column = std::max(column, code.size() + 2);
    }
  }
  for (const auto& [code, comment] : lines) {
    out += code;
    if (!comment.empty()) {
      out += std::string(code.size() < column ? column - code.size() : 2, ' ') + "# " + comment;
    }
    out += "\n";
  }
  return out;
}

std::string describe_params(const ParamDoc& doc) {
  constexpr std::size_t kMaxDefaultWidth = 24;
  std::vector<std::array<std::string, 6>> rows;
  rows.push_back({"KEY", "TYPE", "DEFAULT", "UNIT", "RANGE", "DESCRIPTION"});
  for (const ParamInfo& info : doc.params) {
    std::string shown = info.default_yaml;
    if (shown.size() > kMaxDefaultWidth) {
      shown = shown.substr(0, kMaxDefaultWidth - 3) + "...";
    }
    rows.push_back({info.key, info.type, shown, info.unit.empty() ? "-" : info.unit,
                    info.range.empty() ? "-" : info.range, info.description});
  }
  std::array<std::size_t, 6> width{};
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      width[i] = std::max(width[i], row[i].size());
    }
  }
  std::string out;
  for (const auto& row : rows) {
    for (std::size_t i = 0; i + 1 < row.size(); ++i) {
      out += row[i] + std::string(width[i] - row[i].size() + 2, ' ');
    }
    out += row.back() + "\n";
  }
  return out;
}

}  // namespace robodds::params
