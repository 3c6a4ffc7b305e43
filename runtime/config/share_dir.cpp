#include "runtime/config/share_dir.hpp"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include <unistd.h>

namespace robodds {

std::string this_executable() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  if (n <= 0) {
    return "";
  }
  return std::string(buf, static_cast<std::size_t>(n));
}

std::string find_share_dir(const char* env_share_dir, const std::string& executable_path,
                           const std::string& source_dir) {
  if (env_share_dir != nullptr && *env_share_dir != '\0') {
    return env_share_dir;
  }
  if (!executable_path.empty()) {
    namespace fs = std::filesystem;
    const fs::path installed =
        (fs::path(executable_path).parent_path() / kInstalledShareDirFromExecutable).lexically_normal();
    std::error_code error;  // unreadable counts as absent: fall through to the source dir
    if (fs::is_regular_file(installed / kShareDirMarker, error)) {
      return installed.string();
    }
  }
  return source_dir;
}

std::string share_dir_of_this_process(const std::string& source_dir) {
  return find_share_dir(std::getenv("ROBODDS_SHARE_DIR"), this_executable(), source_dir);
}

}  // namespace robodds
