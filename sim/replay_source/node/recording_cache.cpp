#include "sim/replay_source/node/recording_cache.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>

#include "runtime/mcap/crc32.hpp"

namespace robodds::replay_source {

std::optional<FileStamp> file_stamp(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  struct stat st {};
  std::optional<FileStamp> out;
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
    FileStamp s;
    s.device = static_cast<std::uint64_t>(st.st_dev);
    s.inode = static_cast<std::uint64_t>(st.st_ino);
    s.size = static_cast<std::uint64_t>(st.st_size);
    s.mtime_ns = static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1'000'000'000 + st.st_mtim.tv_nsec;
    s.ctime_ns = static_cast<std::int64_t>(st.st_ctim.tv_sec) * 1'000'000'000 + st.st_ctim.tv_nsec;
    char tail[4096];
    const std::uint64_t want = std::min<std::uint64_t>(s.size, sizeof tail);
    const ssize_t got = ::pread(fd, tail, static_cast<std::size_t>(want), static_cast<off_t>(s.size - want));
    if (got == static_cast<ssize_t>(want)) {
      s.tail_crc = mcap::crc32(tail, static_cast<std::size_t>(want));
      out = s;
    }
  }
  ::close(fd);
  return out;
}

}  // namespace robodds::replay_source
