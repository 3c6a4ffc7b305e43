#pragma once
// What `robodds info FILE.mcap` prints: the text is a pure function of the read report, so it is
// tested without files.

#include <string>

#include "runtime/mcap/mcap_reader.hpp"

namespace robodds::mcap {

/// Channels (topic, schema name and encoding, message encoding, messages, rate), times, chunks
/// and their compression, summary and CRC status; for a damaged file, what was recovered and each
/// problem. Times are printed as seconds (log_time / 1e9).
std::string format_info(const ReadReport& report);

/// Messages per second of one channel: (n - 1) intervals over its first-to-last log time; 0 when
/// it has fewer than two messages or they share one time.
double channel_rate_hz(const ChannelCounts& counts);

}  // namespace robodds::mcap
