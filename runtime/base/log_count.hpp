#pragma once
// How many warnings and errors this process's log wrote (log.hpp), for a command's closing
// report ("2 warnings logged above"). Apart from log.hpp so that the many files including that
// one do not depend on it.

#include <cstdint>

namespace robodds::log {

/// Messages at kWarn or kError written so far (those below the level are not counted).
std::uint64_t warnings_written();

}  // namespace robodds::log
