#pragma once
// Where the binary finds its data files: deploy/qos/robodds_qos.xml, the components' documented
// parameter defaults (<share dir>/<defaults_file>, for users to copy), the scenarios and sim/report/report.py. They sit at
// the same relative paths in the source tree and in an installed share dir (cmake --install,
// the Debian package), so one directory name is all the runtime needs.

#include <string>

namespace robodds {

/// The installed share dir relative to the directory of the installed executable: install()
/// puts the binary into <prefix>/bin and the data into <prefix>/share/robodds
/// (cmake/RoboddsHelpers.cmake, ROBODDS_INSTALL_SHARE_DIR); the two must agree.
inline constexpr const char* kInstalledShareDirFromExecutable = "../share/robodds";

/// The file whose presence marks a share dir as complete enough to use.
inline constexpr const char* kShareDirMarker = "deploy/qos/robodds_qos.xml";

/// The share dir, first match wins:
///  1. `env_share_dir` ($ROBODDS_SHARE_DIR) if not null and not empty, taken as given;
///  2. <directory of executable_path>/../share/robodds if it holds kShareDirMarker (an
///     installed binary), lexically normalised (e.g. /usr/bin/robodds -> /usr/share/robodds);
///  3. `source_dir` (a binary in its build tree: the repository it was built from).
/// `executable_path` may be empty (unknown): then step 2 is skipped. Never throws; a share dir
/// that lacks a file is reported by whoever opens that file, naming it.
std::string find_share_dir(const char* env_share_dir, const std::string& executable_path,
                           const std::string& source_dir);

/// The path of the running executable (/proc/self/exe, symbolic links resolved), or "" when
/// /proc is not available.
std::string this_executable();

/// find_share_dir for this process: $ROBODDS_SHARE_DIR and the executable /proc/self/exe
/// (symbolic links resolved, so a link to an installed binary finds that binary's share dir).
std::string share_dir_of_this_process(const std::string& source_dir);

}  // namespace robodds
