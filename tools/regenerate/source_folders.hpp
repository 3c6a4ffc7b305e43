#pragma once
// Which folders of the source tree README.md's Layout must list: the rule of its drift test
// (tools/regenerate/test/layout_doc_test.cpp), stated once here and in the README.

#include <filesystem>
#include <string>
#include <vector>

namespace robodds {

/// The folders below `root` that hold code, relative to it, '/'-separated and ending in '/'
/// ("common/model/"), sorted. A folder holds code when a CMakeLists.txt or a source file (.cpp,
/// .hpp, .h, .py, .sh, .cmake, .in, .idl) sits at its top, unless its one file is a
/// CMakeLists.txt: such a folder only adds its subfolders, which are judged on their own. Every
/// depth is walked, except
///   - hidden folders (.git, .ci, ...) and, at the top, build trees (build*/);
///   - the conventional parts of a folder below the top, test/, node/, config/ and bench/, and
///     what they hold: the Layout describes them once for every folder.
std::vector<std::string> folders_holding_code(const std::filesystem::path& root);

}  // namespace robodds
