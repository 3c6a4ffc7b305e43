#include "runtime/base/log.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <mutex>

#include "runtime/base/error.hpp"
#include "runtime/base/log_count.hpp"

namespace robodds {

std::string located(const std::string& file, const std::string& key, const std::string& reason) {
  std::string out = file;
  if (!key.empty()) {
    out += (out.empty() ? "" : ": ") + key;
  }
  return out + (out.empty() ? "" : ": ") + reason;
}

namespace log {
namespace {

Level initial_level() {
  const char* env = std::getenv("ROBODDS_LOG");
  if (env == nullptr) {
    return Level::kInfo;
  }
  try {
    return parse_level(env);
  } catch (const ConfigError&) {
    return Level::kInfo;
  }
}

std::atomic<int>& level_storage() {
  static std::atomic<int> storage{static_cast<int>(initial_level())};
  return storage;
}

std::atomic<std::uint64_t> warnings{0};

std::mutex& output_mutex() {
  static std::mutex mutex;
  return mutex;
}

const char* tag(Level level) {
  switch (level) {
    case Level::kDebug: return "debug";
    case Level::kInfo: return "info";
    case Level::kWarn: return "warn";
    case Level::kError: return "error";
  }
  return "?";
}

}  // namespace

void set_level(Level level) { level_storage() = static_cast<int>(level); }
std::uint64_t warnings_written() { return warnings.load(); }
Level level() { return static_cast<Level>(level_storage().load()); }

Level parse_level(const std::string& text) {
  if (text == "debug") return Level::kDebug;
  if (text == "info") return Level::kInfo;
  if (text == "warn") return Level::kWarn;
  if (text == "error") return Level::kError;
  throw ConfigError("log level '" + text + "' is not one of debug, info, warn, error");
}

void write(Level message_level, const std::string& source, const std::string& message) {
  if (static_cast<int>(message_level) < level_storage().load()) {
    return;
  }
  if (message_level >= Level::kWarn) {
    ++warnings;
  }
  std::lock_guard<std::mutex> lock(output_mutex());
  std::fprintf(stderr, "[%s] %s: %s\n", tag(message_level), source.c_str(), message.c_str());
}

}  // namespace log
}  // namespace robodds
