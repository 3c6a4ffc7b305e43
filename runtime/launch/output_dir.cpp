#include "runtime/launch/output_dir.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "runtime/base/error.hpp"

namespace robodds {

void make_output_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(dir, error);
  if (fs::exists(status) && !fs::is_directory(status)) {
    throw ConfigError(located(dir, "", "the output directory is not a directory (a file of that name exists)"));
  }
  fs::create_directories(dir, error);
  if (error) {
    throw ConfigError(located(dir, "", "cannot create the output directory: " + error.message()));
  }
  // Writable? Try it: the mode bits do not tell (root writes into a 0555 directory; /proc and
  // read-only mounts refuse everyone). A name of its own for every probe (mkstemp): hosts in
  // containers sharing one output volume have the same process ids, and a probe named by the pid
  // made one of them fail with "File exists" (containers.compose_e2e, 2026-12-08).
  std::string probe = dir + "/.robodds-write-probe-XXXXXX";
  const int fd = ::mkstemp(probe.data());
  if (fd < 0) {
    throw ConfigError(located(dir, "", std::string("the output directory is not writable: ") + std::strerror(errno)));
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

}  // namespace robodds
