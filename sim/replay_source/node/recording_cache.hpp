#pragma once
// A recording decoded once per process. `robodds run` configures a replay source three times, each
// a new component object: the producer check's and produced_instances()' dry configures, then the
// run's (runtime/launch/launch.cpp); each needs what the recording holds. The key is the file's
// path, identity and content stamp and what was asked of it, so a file rewritten between two uses
// is read again.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace robodds::replay_source {

/// What identifies a file's content without reading all of it.
struct FileStamp {
  std::uint64_t device = 0, inode = 0, size = 0;  // size in bytes
  std::int64_t mtime_ns = 0, ctime_ns = 0;
  // CRC-32 of its last 4 KiB (an MCAP file's footer and summary): a rewrite of the same size within
  // one tick of the file system's clock (ms) keeps the times.
  std::uint32_t tail_crc = 0;
  bool operator==(const FileStamp& o) const {
    return device == o.device && inode == o.inode && size == o.size && mtime_ns == o.mtime_ns && ctime_ns == o.ctime_ns &&
           tail_crc == o.tail_crc;
  }
};

/// The file's stamp; nullopt when it cannot be opened or read (the reader then says why).
std::optional<FileStamp> file_stamp(const std::string& path);

/// The last `capacity` values loaded, by (path, its stamp, `what`): what a caller asks of the file,
/// e.g. its topics. Thread-safe; a load runs under the lock (two components of one file wait for
/// one load). A load that throws stores nothing.
template <class T>
class RecordingCache {
 public:
  explicit RecordingCache(std::size_t capacity) : capacity_(capacity) {}

  std::shared_ptr<const T> get(const std::string& path, const std::string& what,
                               const std::function<std::shared_ptr<const T>()>& load) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const std::optional<FileStamp> stamp = file_stamp(path);  // before the load: a change during it misses next time
    if (!stamp) return load();
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      if (entries_[i].path == path && entries_[i].what == what && entries_[i].stamp == *stamp) {
        Entry hit = std::move(entries_[i]);  // most recently used last
        entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(i));
        entries_.push_back(std::move(hit));
        return entries_.back().value;
      }
    }
    std::shared_ptr<const T> value = load();
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      if (entries_[i].path == path && entries_[i].what == what) {
        entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(i));  // an older content of the file
        break;
      }
    }
    if (entries_.size() >= capacity_ && !entries_.empty()) entries_.erase(entries_.begin());
    if (capacity_ > 0) entries_.push_back(Entry{path, what, *stamp, value});
    return value;
  }

 private:
  struct Entry {
    std::string path, what;
    FileStamp stamp;
    std::shared_ptr<const T> value;
  };
  std::size_t capacity_;
  std::mutex mutex_;
  std::vector<Entry> entries_;  // least recently used first
};

}  // namespace robodds::replay_source
