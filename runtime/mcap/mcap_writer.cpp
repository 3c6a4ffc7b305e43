#include "runtime/mcap/mcap_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

#include "runtime/mcap/crc32.hpp"
#include "runtime/mcap/records.hpp"

namespace robodds::mcap {
namespace {

// A chunk larger than this would make readers allocate that much at once per chunk.
constexpr std::uint64_t kMaxChunkSizeBytes = std::uint64_t{1} << 30;

struct SchemaRecord {
  std::string name, encoding, data;
};
struct ChannelRecord {
  std::uint16_t schema_id;
  std::string topic, message_encoding;
  std::map<std::string, std::string> metadata;
};
struct ChunkIndexRecord {
  std::uint64_t start_time, end_time, chunk_start, chunk_length;
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;
  std::uint64_t message_index_length;
  std::string compression;
  std::uint64_t compressed_size, uncompressed_size;
};

void append_schema(RecordBuilder& b, std::uint16_t id, const SchemaRecord& s) {
  const std::size_t at = b.begin_record(Opcode::kSchema);
  b.u16(id);
  b.str(s.name);
  b.str(s.encoding);
  b.str(s.data);  // Bytes with a uint32 length: the same encoding as a String
  b.end_record(at);
}

void append_channel(RecordBuilder& b, std::uint16_t id, const ChannelRecord& c) {
  const std::size_t at = b.begin_record(Opcode::kChannel);
  b.u16(id);
  b.u16(c.schema_id);
  b.str(c.topic);
  b.str(c.message_encoding);
  const std::size_t map_at = b.begin_u32_length();
  for (const auto& [key, value] : c.metadata) {  // std::map: sorted keys, so the bytes are deterministic
    b.str(key);
    b.str(value);
  }
  b.end_u32_length(map_at);
  b.end_record(at);
}

}  // namespace

void WriterOptions::validate() const {
  if (chunk_size_bytes == 0 || chunk_size_bytes > kMaxChunkSizeBytes) {
    throw ConfigError("WriterOptions.chunk_size_bytes: " + std::to_string(chunk_size_bytes) + " is outside 1.." +
                      std::to_string(kMaxChunkSizeBytes) + " bytes");
  }
  if (compression != Compression::kNone && compression != Compression::kZstd && compression != Compression::kLz4) {
    throw ConfigError("WriterOptions.compression: not one of none, zstd, lz4");
  }
}

struct Writer::Impl {
  std::string path;
  WriterOptions options;
  int fd = -1;
  bool closed = false;
  std::uint64_t file_bytes = 0;
  std::uint32_t data_crc = 0;  // CRC of every byte written so far (the data section until close)

  std::vector<SchemaRecord> schemas;    // id = index + 1
  std::vector<ChannelRecord> channels;  // id = index + 1

  // The open chunk: its uncompressed records, and per channel (index = id - 1) the (log time,
  // offset in the records) of each message for the Message Index records. Vectors by id rather
  // than maps and sets: looked up for every message; cleared, not freed, when a chunk is written.
  std::string chunk;
  std::uint64_t chunk_messages = 0;
  std::uint64_t chunk_start_time = 0, chunk_end_time = 0;
  std::vector<std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index;
  std::vector<bool> chunk_schemas, chunk_channels;  // defined in the open chunk (index = id - 1)
  std::string out;  // a chunk compressed and framed, with its message indexes (capacity reused)

  std::vector<ChunkIndexRecord> chunk_indexes;
  Statistics stats;

  void write_all(const std::string& bytes) {
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
      const ssize_t n = ::write(fd, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        throw McapError(at_byte(path, file_bytes, std::string("write failed: ") + std::strerror(errno)));
      }
      p += n;
      left -= static_cast<std::size_t>(n);
      file_bytes += static_cast<std::uint64_t>(n);
    }
    data_crc = crc32_update(data_crc, bytes.data(), bytes.size());
  }

  void flush_chunk() {
    if (chunk.empty()) return;
    const std::uint32_t uncompressed_crc = crc32(chunk.data(), chunk.size());
    const std::string compression = record_name(options.compression);
    out.clear();
    RecordBuilder b(out);
    const std::size_t record_at = b.begin_record(Opcode::kChunk);
    b.u64(chunk_start_time);
    b.u64(chunk_end_time);
    b.u64(chunk.size());
    b.u32(uncompressed_crc);
    b.str(compression);
    const std::size_t records_length_at = b.size();
    b.u64(0);
    compress_append(options.compression, chunk.data(), chunk.size(), out);
    const std::uint64_t compressed_size = out.size() - records_length_at - 8;
    b.patch_u64(records_length_at, compressed_size);
    b.end_record(record_at);
    const std::uint64_t chunk_length = out.size();

    ChunkIndexRecord index{chunk_start_time, chunk_end_time, file_bytes, chunk_length, {}, 0,
                           compression,      compressed_size, chunk.size()};
    for (std::size_t i = 0; i < chunk_index.size(); ++i) {
      auto& entries = chunk_index[i];
      if (entries.empty()) continue;  // no message of this channel in the chunk
      const auto channel_id = static_cast<std::uint16_t>(i + 1);
      // Sorted by log time (stable: equal times keep their order), so an indexed reader can merge
      // chunks in log-time order even when messages arrived out of order.
      // A recorder's log times mostly come in order already: only then is the sort skipped.
      const auto by_time = [](const auto& a, const auto& c) { return a.first < c.first; };
      if (!std::is_sorted(entries.begin(), entries.end(), by_time)) {
        std::stable_sort(entries.begin(), entries.end(), by_time);
      }
      index.message_index_offsets[channel_id] = file_bytes + out.size();
      const std::size_t at = b.begin_record(Opcode::kMessageIndex);
      b.u16(channel_id);
      const std::size_t array_at = b.begin_u32_length();
      for (const auto& [log_time, offset] : entries) {
        b.u64(log_time);
        b.u64(offset);
      }
      b.end_u32_length(array_at);
      b.end_record(at);
    }
    index.message_index_length = out.size() - chunk_length;
    write_all(out);  // the chunk and its indexes in one write(2): complete on disk or not at all
    chunk_indexes.push_back(std::move(index));
    ++stats.chunk_count;
    chunk.clear();
    chunk_messages = 0;
    for (auto& entries : chunk_index) entries.clear();
    chunk_schemas.assign(chunk_schemas.size(), false);
    chunk_channels.assign(chunk_channels.size(), false);
  }

  void check_open(const char* what) const {
    if (closed) throw McapError(path + ": " + what + " after close()");
  }
};

Writer::Writer(const std::string& path, const WriterOptions& options) : impl_(std::make_unique<Impl>()) {
  options.validate();
  impl_->path = path;
  impl_->options = options;
  impl_->fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (impl_->fd < 0) throw McapError(path + ": cannot create the MCAP file: " + std::strerror(errno));
  std::string out(kMagic, kMagicSize);
  RecordBuilder b(out);
  const std::size_t at = b.begin_record(Opcode::kHeader);
  b.str(options.profile);
  b.str(options.library);
  b.end_record(at);
  try {
    impl_->write_all(out);
  } catch (...) {
    ::close(impl_->fd);
    throw;
  }
}

Writer::~Writer() {
  try {
    close();
  } catch (...) {
    // A destructor must not throw; close() explicitly to see write errors.
  }
  if (impl_ && impl_->fd >= 0) ::close(impl_->fd);
}

std::uint16_t Writer::add_schema(const std::string& name, const std::string& encoding, const std::string& data) {
  impl_->check_open("add_schema");
  if (impl_->schemas.size() >= std::numeric_limits<std::uint16_t>::max()) {
    throw McapError(impl_->path + ": more than 65535 schemas");
  }
  impl_->schemas.push_back({name, encoding, data});
  impl_->chunk_schemas.push_back(false);
  return static_cast<std::uint16_t>(impl_->schemas.size());
}

std::uint16_t Writer::add_channel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                                  const std::map<std::string, std::string>& metadata) {
  impl_->check_open("add_channel");
  if (schema_id > impl_->schemas.size()) {
    throw McapError(impl_->path + ": add_channel(" + topic + "): unknown schema id " + std::to_string(schema_id));
  }
  if (impl_->channels.size() >= std::numeric_limits<std::uint16_t>::max()) {
    throw McapError(impl_->path + ": more than 65535 channels");
  }
  impl_->channels.push_back({schema_id, topic, message_encoding, metadata});
  impl_->chunk_channels.push_back(false);
  impl_->chunk_index.emplace_back();
  const auto id = static_cast<std::uint16_t>(impl_->channels.size());
  impl_->stats.channel_message_counts[id] = 0;
  return id;
}

void Writer::write(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time_ns,
                   std::uint64_t publish_time_ns, const std::uint8_t* data, std::size_t size) {
  Impl& w = *impl_;
  w.check_open("write");
  if (channel_id == 0 || channel_id > w.channels.size()) {
    throw McapError(w.path + ": write: unknown channel id " + std::to_string(channel_id));
  }
  RecordBuilder b(w.chunk);
  // Each chunk carries the Schema and Channel records of its messages, so every chunk can be
  // decoded alone (a file cut short, a chunk lost to corruption).
  if (!w.chunk_channels[channel_id - 1U]) {
    w.chunk_channels[channel_id - 1U] = true;
    const ChannelRecord& channel = w.channels[channel_id - 1U];
    if (channel.schema_id != 0 && !w.chunk_schemas[channel.schema_id - 1U]) {
      w.chunk_schemas[channel.schema_id - 1U] = true;
      append_schema(b, channel.schema_id, w.schemas[channel.schema_id - 1U]);
    }
    append_channel(b, channel_id, channel);
  }
  if (w.chunk_messages++ == 0) {
    w.chunk_start_time = log_time_ns;
    w.chunk_end_time = log_time_ns;
  }
  w.chunk_start_time = std::min(w.chunk_start_time, log_time_ns);
  w.chunk_end_time = std::max(w.chunk_end_time, log_time_ns);
  w.chunk_index[channel_id - 1U].emplace_back(log_time_ns, w.chunk.size());
  const std::size_t at = b.begin_record(Opcode::kMessage);
  b.u16(channel_id);
  b.u32(sequence);
  b.u64(log_time_ns);
  b.u64(publish_time_ns);
  b.raw(data, size);
  b.end_record(at);

  Statistics& s = w.stats;
  if (s.message_count == 0) {
    s.message_start_time = log_time_ns;
    s.message_end_time = log_time_ns;
  }
  s.message_start_time = std::min(s.message_start_time, log_time_ns);
  s.message_end_time = std::max(s.message_end_time, log_time_ns);
  ++s.message_count;
  ++s.channel_message_counts[channel_id];
  if (w.chunk.size() >= w.options.chunk_size_bytes) w.flush_chunk();
}

void Writer::close() {
  Impl& w = *impl_;
  if (w.closed) return;
  w.closed = true;  // even if a write below fails: a second close() must not write a second summary
  w.flush_chunk();

  std::string out;
  RecordBuilder b(out);
  std::size_t at = b.begin_record(Opcode::kDataEnd);
  b.u32(w.data_crc);
  b.end_record(at);
  const std::uint64_t summary_start = w.file_bytes + out.size();

  // Summary: one group per record kind, each remembered for its Summary Offset record.
  std::vector<std::pair<Opcode, std::pair<std::uint64_t, std::uint64_t>>> groups;  // opcode, (start, length)
  auto group = [&](Opcode op, std::size_t begin) {
    if (out.size() > begin) groups.push_back({op, {w.file_bytes + begin, out.size() - begin}});
  };
  std::size_t begin = out.size();
  for (std::size_t i = 0; i < w.schemas.size(); ++i) append_schema(b, static_cast<std::uint16_t>(i + 1), w.schemas[i]);
  group(Opcode::kSchema, begin);
  begin = out.size();
  for (std::size_t i = 0; i < w.channels.size(); ++i) append_channel(b, static_cast<std::uint16_t>(i + 1), w.channels[i]);
  group(Opcode::kChannel, begin);

  begin = out.size();
  Statistics& s = w.stats;
  s.schema_count = static_cast<std::uint16_t>(w.schemas.size());
  s.channel_count = static_cast<std::uint32_t>(w.channels.size());
  at = b.begin_record(Opcode::kStatistics);
  b.u64(s.message_count);
  b.u16(s.schema_count);
  b.u32(s.channel_count);
  b.u32(s.attachment_count);
  b.u32(s.metadata_count);
  b.u32(s.chunk_count);
  b.u64(s.message_start_time);
  b.u64(s.message_end_time);
  std::size_t map_at = b.begin_u32_length();
  for (const auto& [channel_id, count] : s.channel_message_counts) {
    b.u16(channel_id);
    b.u64(count);
  }
  b.end_u32_length(map_at);
  b.end_record(at);
  group(Opcode::kStatistics, begin);

  begin = out.size();
  for (const ChunkIndexRecord& c : w.chunk_indexes) {
    at = b.begin_record(Opcode::kChunkIndex);
    b.u64(c.start_time);
    b.u64(c.end_time);
    b.u64(c.chunk_start);
    b.u64(c.chunk_length);
    map_at = b.begin_u32_length();
    for (const auto& [channel_id, offset] : c.message_index_offsets) {
      b.u16(channel_id);
      b.u64(offset);
    }
    b.end_u32_length(map_at);
    b.u64(c.message_index_length);
    b.str(c.compression);
    b.u64(c.compressed_size);
    b.u64(c.uncompressed_size);
    b.end_record(at);
  }
  group(Opcode::kChunkIndex, begin);

  const std::uint64_t summary_offset_start = w.file_bytes + out.size();
  for (const auto& [op, range] : groups) {
    at = b.begin_record(Opcode::kSummaryOffset);
    b.u8(static_cast<std::uint8_t>(op));
    b.u64(range.first);
    b.u64(range.second);
    b.end_record(at);
  }
  // The footer's length is written up front (not patched afterwards): the summary CRC covers it.
  b.u8(static_cast<std::uint8_t>(Opcode::kFooter));
  b.u64(kFooterContentSize);
  b.u64(summary_start);
  b.u64(summary_offset_start);
  // The summary CRC covers the summary, the summary offsets and the footer up to this field.
  const std::size_t summary_begin = static_cast<std::size_t>(summary_start - w.file_bytes);
  b.u32(crc32(out.data() + summary_begin, out.size() - summary_begin));
  b.raw(kMagic, kMagicSize);
  w.write_all(out);
  if (::close(w.fd) != 0) {
    w.fd = -1;
    throw McapError(w.path + ": close failed: " + std::strerror(errno));
  }
  w.fd = -1;
}

std::uint64_t Writer::file_bytes() const { return impl_->file_bytes; }
std::uint64_t Writer::message_count() const { return impl_->stats.message_count; }

}  // namespace robodds::mcap
