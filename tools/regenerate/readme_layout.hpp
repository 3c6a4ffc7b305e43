#pragma once
// README.md's Layout against the source tree: every folder that holds code has a row (generated
// or hand-written), and every folder a row names exists. Checked by
// tools/regenerate/test/layout_doc_test.cpp.

#include <filesystem>
#include <string>
#include <vector>

namespace robodds {

/// A row of a Layout table: its first cell, a folder in backquotes, and the rest of the row.
struct LayoutRow {
  std::string folder;  // as written, relative to the repository root: "common/model/"
  std::string text;    // the other cells, as written
};

/// The rows of every table of the section "## Layout" of `readme` whose first cell is a folder
/// in backquotes ending in '/'; header and separator rows are not. In the order of the README.
std::vector<LayoutRow> layout_rows(const std::string& readme);

/// What disagrees between `rows` and the tree at `root`, one readable line each (none: they agree):
///   - a folder of `folders_holding_code` (source_folders.hpp) with no row, unless a row of its
///     parent names it as `<name>/` (as runtime/'s row names `bus/`; a folder may have two rows,
///     a generated one and a hand-written one);
///   - a row whose folder does not exist below `root`.
std::vector<std::string> layout_problems(const std::vector<LayoutRow>& rows,
                                         const std::vector<std::string>& folders_holding_code,
                                         const std::filesystem::path& root);

}  // namespace robodds
