#include "tools/regenerate/readme_layout.hpp"

#include <algorithm>
#include <sstream>

namespace robodds {
namespace {

bool in_backquotes(const std::string& cell) {
  return cell.size() > 2 && cell.front() == '`' && cell.back() == '`';
}

/// "| `a/` | b | c |" -> {"a/", "b | c |"}; false for any other line.
bool parse_row(const std::string& line, LayoutRow& row) {
  if (line.rfind("| ", 0) != 0) {
    return false;
  }
  const std::size_t cell_end = line.find(" | ", 2);
  if (cell_end == std::string::npos) {
    return false;
  }
  const std::string cell = line.substr(2, cell_end - 2);
  if (!in_backquotes(cell) || cell[cell.size() - 2] != '/') {
    return false;
  }
  row = {cell.substr(1, cell.size() - 2), line.substr(cell_end + 3)};
  return true;
}

bool has_row(const std::vector<LayoutRow>& rows, const std::string& folder) {
  return std::any_of(rows.begin(), rows.end(), [&](const LayoutRow& row) { return row.folder == folder; });
}

/// Whether a row of `folder` (a folder may have a generated row and a hand-written one) names
/// `name` in backquotes.
bool named_in_a_row_of(const std::vector<LayoutRow>& rows, const std::string& folder, const std::string& name) {
  return std::any_of(rows.begin(), rows.end(), [&](const LayoutRow& row) {
    return row.folder == folder && row.text.find("`" + name + "`") != std::string::npos;
  });
}

/// "runtime/bus/" -> {"runtime/", "bus/"}; the parent of a top folder is "".
std::pair<std::string, std::string> parent_and_name(const std::string& folder) {
  const std::size_t slash = folder.rfind('/', folder.size() - 2);
  return slash == std::string::npos ? std::make_pair(std::string(), folder)
                                    : std::make_pair(folder.substr(0, slash + 1), folder.substr(slash + 1));
}

bool listed(const std::vector<LayoutRow>& rows, const std::string& folder) {
  const auto [parent, name] = parent_and_name(folder);
  return has_row(rows, folder) || named_in_a_row_of(rows, parent, name);
}

}  // namespace

std::vector<LayoutRow> layout_rows(const std::string& readme) {
  std::vector<LayoutRow> rows;
  std::istringstream in(readme);
  bool in_layout = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("## ", 0) == 0) {
      in_layout = line == "## Layout";
      continue;
    }
    LayoutRow row;
    if (in_layout && parse_row(line, row)) {
      rows.push_back(row);
    }
  }
  return rows;
}

std::vector<std::string> layout_problems(const std::vector<LayoutRow>& rows,
                                         const std::vector<std::string>& folders_holding_code,
                                         const std::filesystem::path& root) {
  std::vector<std::string> problems;
  for (const std::string& folder : folders_holding_code) {
    if (!listed(rows, folder)) {
      const auto [parent, name] = parent_and_name(folder);
      problems.push_back("`" + folder + "` holds code but has no row" +
                         (parent.empty() ? std::string() : ", and no row of `" + parent + "` names `" + name + "`"));
    }
  }
  for (const LayoutRow& row : rows) {
    if (!std::filesystem::is_directory(root / row.folder)) {
      problems.push_back("`" + row.folder + "` has a row but is no folder of the source tree");
    }
  }
  return problems;
}

}  // namespace robodds
