#include "tools/regenerate/source_folders.hpp"

#include <algorithm>
#include <set>

namespace robodds {
namespace {

namespace fs = std::filesystem;

bool is_source_file(const fs::path& file) {
  static const std::set<std::string> kSourceExtensions = {".cpp", ".hpp", ".h", ".py", ".sh", ".cmake", ".in", ".idl"};
  return file.filename() == "CMakeLists.txt" || kSourceExtensions.count(file.extension().string()) > 0;
}

bool holds_code(const fs::path& folder) {
  int files = 0;
  bool source = false;
  bool only_cmake_lists = true;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (!entry.is_regular_file()) {
      continue;
    }
    ++files;
    source = source || is_source_file(entry.path());
    only_cmake_lists = only_cmake_lists && entry.path().filename() == "CMakeLists.txt";
  }
  return source && !(files == 1 && only_cmake_lists);
}

/// Whether the walk skips `folder` (at `depth`, 1 for the top) and everything below it.
bool skipped(const fs::path& folder, int depth) {
  static const std::set<std::string> kConventionalParts = {"test", "node", "config", "bench"};
  const std::string name = folder.filename().string();
  return name.front() == '.' || (depth == 1 && name.rfind("build", 0) == 0) ||
         (depth > 1 && kConventionalParts.count(name) > 0);
}

void walk(const fs::path& root, const fs::path& folder, int depth, std::vector<std::string>& found) {
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (!entry.is_directory() || entry.is_symlink() || skipped(entry.path(), depth)) {
      continue;
    }
    if (holds_code(entry.path())) {
      found.push_back(entry.path().lexically_relative(root).generic_string() + "/");
    }
    walk(root, entry.path(), depth + 1, found);
  }
}

}  // namespace

std::vector<std::string> folders_holding_code(const fs::path& root) {
  std::vector<std::string> found;
  walk(root, root, 1, found);
  std::sort(found.begin(), found.end());
  return found;
}

}  // namespace robodds
