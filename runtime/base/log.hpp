#pragma once
// Minimal thread-safe logging to stderr. Components log through their context; the level is
// set once per process (ROBODDS_LOG=debug|info|warn|error, default info).

#include <string>

namespace robodds::log {

enum class Level { kDebug = 0, kInfo = 1, kWarn = 2, kError = 3 };

void set_level(Level level);
Level level();
/// Parses "debug", "info", "warn" or "error"; throws ConfigError otherwise.
Level parse_level(const std::string& text);
void write(Level level, const std::string& source, const std::string& message);

inline void debug(const std::string& source, const std::string& message) { write(Level::kDebug, source, message); }
inline void info(const std::string& source, const std::string& message) { write(Level::kInfo, source, message); }
inline void warn(const std::string& source, const std::string& message) { write(Level::kWarn, source, message); }
inline void error(const std::string& source, const std::string& message) { write(Level::kError, source, message); }

}  // namespace robodds::log
