#pragma once
// Reads MCAP files: every record from the start (chunks decompressed, their CRCs checked), then
// the summary, which is checked against what was read (summary CRC, statistics, chunk indexes,
// message indexes, data section CRC). A file without summary or footer, or cut in the middle of a
// record (a recorder killed with SIGKILL), yields every complete chunk before the cut, and the
// report says what was recovered.
//
// Two modes: kStrict throws McapError on anything short of a whole, valid file; kRecover reads
// what it can and lists each problem ("FILE: byte N: reason") in the report. Both throw when
// nothing is readable (missing file, not an MCAP file).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "runtime/mcap/mcap_error.hpp"
#include "runtime/mcap/records.hpp"

namespace robodds::mcap {

enum class OnDamage { kStrict, kRecover };

struct SchemaInfo {
  std::uint16_t id = 0;
  std::string name, encoding, data;
};

struct ChannelInfo {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;
  std::string topic, message_encoding;
  std::map<std::string, std::string> metadata;
};

/// One message; `data` points into the reader's buffers and is valid during the callback only.
struct MessageView {
  std::uint16_t channel_id;
  std::uint32_t sequence;
  std::uint64_t log_time;  // ns
  std::uint64_t publish_time;
  const std::uint8_t* data;
  std::size_t size;
  const ChannelInfo* channel;  // the message's channel (defined before it)
};

struct Message {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
  std::vector<std::uint8_t> data;
};

struct ChunkInfo {
  std::uint64_t offset = 0;  // of the Chunk record in the file
  std::uint64_t length = 0;  // of the whole record
  std::string compression;   // as in the record: "", "zstd", "lz4"
  std::uint64_t compressed_size = 0, uncompressed_size = 0;
  std::uint64_t message_start_time = 0, message_end_time = 0;
  std::uint64_t message_count = 0;
};

/// Per channel, counted from the messages read.
struct ChannelCounts {
  std::uint64_t messages = 0;
  std::uint64_t first_log_time = 0, last_log_time = 0;  // ns
  std::uint64_t bytes = 0;                              // message payload bytes
};

struct ReadReport {
  std::string path;
  std::uint64_t file_size = 0;
  std::string profile, library;             // from the Header
  std::vector<SchemaInfo> schemas;          // sorted by id
  std::vector<ChannelInfo> channels;        // sorted by id
  std::vector<ChunkInfo> chunks;            // every chunk whose messages were read, in file order
  std::map<std::uint16_t, ChannelCounts> channel_counts;
  Statistics counted;                       // counted from what was read
  std::optional<Statistics> summary_statistics;  // as the summary states it
  bool footer_present = false;              // Footer and closing magic read
  bool summary_present = false;             // a summary section was found and its CRC matches
  std::optional<std::uint64_t> truncated_at;  // where the records stopped forming a whole file
  std::vector<std::string> problems;        // damage found, one line each; empty for a valid file

  /// True when the file is whole and every check passed.
  bool valid() const { return footer_present && !truncated_at && problems.empty(); }
  /// e.g. "truncated at byte 5120: 12 complete chunks, 3,456 messages recovered; summary missing";
  /// empty for a whole file.
  std::string recovery() const;
};

/// Reads `path`, calling `on_message` for every message in file order (may be empty). A caller
/// that wants a few channels keeps only theirs (MessageView::channel): every record is still read
/// and checked, and the report covers every channel.
ReadReport scan_mcap(const std::string& path, OnDamage on_damage,
                     const std::function<void(const MessageView&)>& on_message);

struct McapContents {
  ReadReport report;
  std::vector<Message> messages;  // in log-time order (stable: equal times keep file order)
};
McapContents read_mcap(const std::string& path, OnDamage on_damage = OnDamage::kStrict);

/// 1234567 -> "1,234,567".
std::string with_thousands(std::uint64_t n);

}  // namespace robodds::mcap
