#pragma once
// Writes MCAP files (https://mcap.dev/spec): magic, Header, then Chunks (each with the Schema and
// Channel records its messages need, then its Message records; zstd, lz4 or uncompressed, CRC of
// the uncompressed records) each followed by its Message Index records, Data End (CRC of the data
// section), the summary (every Schema and Channel, Statistics, Chunk Indexes), Summary Offsets, the
// Footer (with the summary's CRC) and the closing magic. The API is agreed with the recorder
// (/work/notes/mcap_api.md); std, libzstd and liblz4 only.
//
// Each completed chunk, with its message indexes, goes to the file with write(2) as soon as it is
// complete, so a process killed with SIGKILL leaves every completed chunk readable
// (mcap_reader.hpp recovers them).

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "runtime/mcap/compression.hpp"
#include "runtime/mcap/mcap_error.hpp"

namespace robodds::mcap {

struct WriterOptions {
  Compression compression = Compression::kZstd;
  std::uint64_t chunk_size_bytes = 1 << 20;  // uncompressed bytes per chunk before it is closed and written
  std::string profile;                       // MCAP header profile ("" = none)
  std::string library = "robodds";           // MCAP header library
  void validate() const;                     // ConfigError naming the field and reason
};

class Writer {
 public:
  /// Creates/truncates `path`; ConfigError naming the path and strerror on failure.
  Writer(const std::string& path, const WriterOptions& options);
  ~Writer();  // close() if still open, never throws
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  /// Ids count from 1 (0 means "no schema" in MCAP).
  std::uint16_t add_schema(const std::string& name, const std::string& encoding, const std::string& data);
  /// Ids count from 1. `schema_id` must be 0 or a returned schema id.
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata = {});
  /// times in ns since the epoch (or sim ns in lockstep); data copied. Log times need not increase.
  void write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns, std::uint64_t publish_time_ns,
             const std::uint8_t* data, std::size_t size);
  /// Finishes the open chunk, data end, summary (schemas, channels, statistics, chunk indexes),
  /// summary offsets, footer with summary CRC, closing magic. Idempotent.
  void close();
  std::uint64_t file_bytes() const;  // bytes written to the file so far (for --max-size splits)
  std::uint64_t message_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace robodds::mcap
