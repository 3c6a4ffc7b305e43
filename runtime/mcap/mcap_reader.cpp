#include "runtime/mcap/mcap_reader.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <set>

#include "runtime/mcap/compression.hpp"
#include "runtime/mcap/crc32.hpp"

namespace robodds::mcap {
namespace {

/// The file, mapped read-only (a recording can be larger than memory; pages are read on demand).
class MappedFile {
 public:
  explicit MappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw McapError(path + ": cannot open: " + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
      const int e = errno;
      ::close(fd);
      throw McapError(path + ": cannot stat: " + std::strerror(e));
    }
    if (!S_ISREG(st.st_mode)) {
      ::close(fd);
      throw McapError(path + ": not a regular file");
    }
    size_ = static_cast<std::size_t>(st.st_size);
    if (size_ > 0) {
      void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
      if (p == MAP_FAILED) {
        const int e = errno;
        ::close(fd);
        throw McapError(path + ": cannot map: " + std::strerror(e));
      }
      data_ = static_cast<const std::uint8_t*>(p);
    }
    ::close(fd);
  }
  ~MappedFile() {
    if (data_ != nullptr) ::munmap(const_cast<std::uint8_t*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const std::uint8_t* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
};

std::string opcode_name(std::uint8_t op) {
  static const char* const names[] = {"?",          "Header",     "Footer",          "Schema",
                                      "Channel",    "Message",    "Chunk",           "Message Index",
                                      "Chunk Index", "Attachment", "Attachment Index", "Statistics",
                                      "Metadata",   "Metadata Index", "Summary Offset", "Data End"};
  if (op >= 1 && op <= 0x0F) return names[op];
  char buf[32];
  std::snprintf(buf, sizeof buf, "opcode 0x%02x", op);
  return buf;
}

struct ChunkIndexEntry {
  std::uint64_t offset;
  ChunkInfo info;
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;
  std::uint64_t message_index_length;
};

/// The state of one pass over the file.
class Scanner {
 public:
  Scanner(const MappedFile& file, ReadReport& report, OnDamage mode,
          const std::function<void(const MessageView&)>& on_message)
      : file_(file), r_(report), mode_(mode), on_message_(on_message) {}

  void run() {
    const std::uint8_t* d = file_.data();
    const std::size_t size = file_.size();
    if (size < kMagicSize || std::memcmp(d, kMagic, kMagicSize) != 0) {
      throw McapError(at_byte(r_.path, 0, "not an MCAP file (bad magic)"));
    }
    std::size_t pos = kMagicSize;
    bool first = true;
    while (pos < size) {
      if (size - pos < kRecordPrefixSize) {
        truncated(pos, "the last " + std::to_string(size - pos) + " bytes are no whole record");
        break;
      }
      const std::uint8_t op = d[pos];
      std::uint64_t length = 0;
      for (int i = 0; i < 8; ++i) length |= std::uint64_t{d[pos + 1 + static_cast<std::size_t>(i)]} << (8 * i);
      if (length > size - pos - kRecordPrefixSize) {
        truncated(pos, opcode_name(op) + " record of " + std::to_string(length) + " bytes overruns the file (" +
                           std::to_string(size) + " bytes)");
        break;
      }
      if (first && op != static_cast<std::uint8_t>(Opcode::kHeader)) {
        problem(pos, "the first record is " + opcode_name(op) + ", not Header");
      }
      first = false;
      const std::uint8_t* content = d + pos + kRecordPrefixSize;
      const std::size_t end = pos + kRecordPrefixSize + static_cast<std::size_t>(length);
      try {
        if (!record(pos, op, content, static_cast<std::size_t>(length), end)) break;  // footer
      } catch (const FieldReader::FieldOverrun& e) {
        problem(pos, opcode_name(op) + " record: field at content byte " + std::to_string(e.at) +
                         " overruns the record (" + std::to_string(length) + " bytes)");
      }
      pos = end;
    }
    if (!r_.footer_present && !r_.truncated_at) truncated(size, "no Footer");
    finish();
  }

 private:
  void problem(std::uint64_t offset, const std::string& reason) {
    const std::string line = at_byte(r_.path, offset, reason);
    if (mode_ == OnDamage::kStrict) throw McapError(line);
    r_.problems.push_back(line);
  }
  void truncated(std::uint64_t offset, const std::string& reason) {
    r_.truncated_at = offset;
    if (mode_ == OnDamage::kStrict) throw McapError(at_byte(r_.path, offset, "truncated: " + reason));
  }

  void add_schema(std::uint64_t offset, SchemaInfo s) {
    auto [it, inserted] = schemas_.emplace(s.id, s);
    if (!inserted && (it->second.name != s.name || it->second.encoding != s.encoding || it->second.data != s.data)) {
      problem(offset, "Schema " + std::to_string(s.id) + " redefined with other content");
    }
  }
  void add_channel(std::uint64_t offset, ChannelInfo c) {
    auto [it, inserted] = channels_.emplace(c.id, c);
    if (!inserted && (it->second.topic != c.topic || it->second.schema_id != c.schema_id ||
                      it->second.message_encoding != c.message_encoding || it->second.metadata != c.metadata)) {
      problem(offset, "Channel " + std::to_string(c.id) + " redefined with other content");
    }
  }

  static SchemaInfo parse_schema(FieldReader& f) {
    SchemaInfo s;
    s.id = f.u16();
    s.name = f.str();
    s.encoding = f.str();
    s.data = f.str();
    return s;
  }
  static ChannelInfo parse_channel(FieldReader& f) {
    ChannelInfo c;
    c.id = f.u16();
    c.schema_id = f.u16();
    c.topic = f.str();
    c.message_encoding = f.str();
    const std::uint32_t map_bytes = f.u32();
    FieldReader m(f.skip(map_bytes), map_bytes);
    while (m.remaining() > 0) {
      std::string key = m.str();
      c.metadata[key] = m.str();
    }
    return c;
  }

  void message(const MessageView& v) {
    Statistics& s = r_.counted;
    if (s.message_count == 0) s.message_start_time = s.message_end_time = v.log_time;
    s.message_start_time = std::min(s.message_start_time, v.log_time);
    s.message_end_time = std::max(s.message_end_time, v.log_time);
    ++s.message_count;
    ++s.channel_message_counts[v.channel_id];
    ChannelCounts& c = r_.channel_counts[v.channel_id];
    if (c.messages == 0) c.first_log_time = c.last_log_time = v.log_time;
    c.first_log_time = std::min(c.first_log_time, v.log_time);
    c.last_log_time = std::max(c.last_log_time, v.log_time);
    ++c.messages;
    c.bytes += v.size;
    if (on_message_) {
      MessageView with_channel = v;
      with_channel.channel = &channels_.at(v.channel_id);  // defined: checked by the callers
      on_message_(with_channel);
    }
  }

  static MessageView parse_message(FieldReader& f) {
    MessageView v{};
    v.channel_id = f.u16();
    v.sequence = f.u32();
    v.log_time = f.u64();
    v.publish_time = f.u64();
    v.size = f.remaining();
    v.data = f.skip(v.size);
    return v;
  }

  /// Handles one top-level record; false after the Footer.
  bool record(std::uint64_t pos, std::uint8_t op, const std::uint8_t* content, std::size_t length, std::size_t end) {
    FieldReader f(content, length);
    switch (static_cast<Opcode>(op)) {
      case Opcode::kHeader:
        r_.profile = f.str();
        r_.library = f.str();
        break;
      case Opcode::kSchema: {
        SchemaInfo s = parse_schema(f);
        if (in_summary_) summary_schemas_.insert(s.id);
        add_schema(pos, s);
        break;
      }
      case Opcode::kChannel: {
        ChannelInfo c = parse_channel(f);
        if (!in_summary_) {
          if (c.schema_id != 0 && schemas_.count(c.schema_id) == 0) {
            problem(pos, "Channel " + std::to_string(c.id) + " names schema " + std::to_string(c.schema_id) +
                             ", not defined before it");
          }
        } else {
          summary_channels_.insert(c.id);
        }
        add_channel(pos, c);
        break;
      }
      case Opcode::kMessage: {
        const MessageView v = parse_message(f);
        if (channels_.count(v.channel_id) == 0) {
          problem(pos, "Message on channel " + std::to_string(v.channel_id) + ", not defined before it");
        } else {
          message(v);
        }
        break;
      }
      case Opcode::kChunk:
        chunk(pos, f, end);
        break;
      case Opcode::kMessageIndex:
        message_index(pos, f, end);
        break;
      case Opcode::kDataEnd: {
        const std::uint32_t crc = f.u32();
        if (crc != 0 && crc != crc32(file_.data(), static_cast<std::size_t>(pos))) {
          problem(pos, "data section CRC mismatch (Data End says " + std::to_string(crc) + ", bytes give " +
                           std::to_string(crc32(file_.data(), static_cast<std::size_t>(pos))) + ")");
        }
        in_summary_ = true;
        data_end_ = end;
        break;
      }
      case Opcode::kStatistics: {
        Statistics s;
        s.message_count = f.u64();
        s.schema_count = f.u16();
        s.channel_count = f.u32();
        s.attachment_count = f.u32();
        s.metadata_count = f.u32();
        s.chunk_count = f.u32();
        s.message_start_time = f.u64();
        s.message_end_time = f.u64();
        const std::uint32_t map_bytes = f.u32();
        FieldReader m(f.skip(map_bytes), map_bytes);
        while (m.remaining() > 0) {
          const std::uint16_t channel = m.u16();
          s.channel_message_counts[channel] = m.u64();
        }
        r_.summary_statistics = s;
        break;
      }
      case Opcode::kChunkIndex: {
        ChunkIndexEntry e{};
        e.offset = pos;
        e.info.message_start_time = f.u64();
        e.info.message_end_time = f.u64();
        e.info.offset = f.u64();
        e.info.length = f.u64();
        const std::uint32_t map_bytes = f.u32();
        FieldReader m(f.skip(map_bytes), map_bytes);
        while (m.remaining() > 0) {
          const std::uint16_t channel = m.u16();
          e.message_index_offsets[channel] = m.u64();
        }
        e.message_index_length = f.u64();
        e.info.compression = f.str();
        e.info.compressed_size = f.u64();
        e.info.uncompressed_size = f.u64();
        chunk_indexes_.push_back(e);
        break;
      }
      case Opcode::kFooter: {
        footer_at_ = pos;
        footer_summary_start_ = f.u64();
        footer_summary_offset_start_ = f.u64();
        footer_summary_crc_ = f.u32();
        if (file_.size() - end < kMagicSize) {
          truncated(end, "the closing magic is missing");
        } else {
          if (std::memcmp(file_.data() + end, kMagic, kMagicSize) != 0) problem(end, "bad closing magic");
          if (file_.size() - end > kMagicSize) {
            problem(end + kMagicSize, std::to_string(file_.size() - end - kMagicSize) + " bytes after the closing magic");
          }
          r_.footer_present = true;
        }
        return false;
      }
      default:
        break;  // attachments, metadata, summary offsets, records of later versions: not needed here
    }
    return true;
  }

  void chunk(std::uint64_t pos, FieldReader& f, std::size_t end) {
    if (in_summary_) problem(pos, "Chunk after Data End");
    ChunkInfo info;
    info.offset = pos;
    info.length = end - pos;
    info.message_start_time = f.u64();
    info.message_end_time = f.u64();
    info.uncompressed_size = f.u64();
    const std::uint32_t crc = f.u32();
    info.compression = f.str();
    info.compressed_size = f.u64();
    const std::uint8_t* records = f.skip(info.compressed_size);
    std::string reason;
    if (!decompress(info.compression, records, static_cast<std::size_t>(info.compressed_size), info.uncompressed_size,
                    buffer_, reason)) {
      problem(pos, "Chunk: " + reason);
      last_chunk_ok_ = false;
      return;
    }
    if (crc != 0 && crc != crc32(buffer_.data(), buffer_.size())) {
      problem(pos, "Chunk CRC mismatch (record says " + std::to_string(crc) + ", records give " +
                       std::to_string(crc32(buffer_.data(), buffer_.size())) + ")");
      last_chunk_ok_ = false;
      return;
    }
    // Parse all inner records before delivering any message: a chunk counts whole or not at all.
    const auto* d = reinterpret_cast<const std::uint8_t*>(buffer_.data());
    std::vector<std::pair<std::size_t, MessageView>> messages;
    std::vector<SchemaInfo> schemas;
    std::vector<ChannelInfo> channels;
    std::set<std::uint16_t> chunk_channels;
    std::size_t p = 0;
    try {
      while (p < buffer_.size()) {
        if (buffer_.size() - p < kRecordPrefixSize) throw FieldReader::FieldOverrun{p};
        const std::uint8_t op = d[p];
        FieldReader prefix(d + p + 1, 8);
        const std::uint64_t length = prefix.u64();
        if (length > buffer_.size() - p - kRecordPrefixSize) {
          problem(pos, "Chunk: inner " + opcode_name(op) + " record at " + std::to_string(p) + " overruns the chunk");
          last_chunk_ok_ = false;
          return;
        }
        FieldReader rf(d + p + kRecordPrefixSize, static_cast<std::size_t>(length));
        if (op == static_cast<std::uint8_t>(Opcode::kSchema)) {
          schemas.push_back(parse_schema(rf));
        } else if (op == static_cast<std::uint8_t>(Opcode::kChannel)) {
          channels.push_back(parse_channel(rf));
          chunk_channels.insert(channels.back().id);
        } else if (op == static_cast<std::uint8_t>(Opcode::kMessage)) {
          messages.emplace_back(p, parse_message(rf));
        }
        p += kRecordPrefixSize + static_cast<std::size_t>(length);
      }
    } catch (const FieldReader::FieldOverrun& e) {
      problem(pos, "Chunk: inner record at " + std::to_string(p) + ": field overruns it");
      last_chunk_ok_ = false;
      return;
    }
    for (SchemaInfo& s : schemas) add_schema(pos, std::move(s));
    for (ChannelInfo& c : channels) add_channel(pos, std::move(c));
    last_chunk_ = {};
    for (const auto& [offset, v] : messages) {
      if (channels_.count(v.channel_id) == 0) {
        problem(pos, "Chunk: Message on channel " + std::to_string(v.channel_id) + ", not defined before it");
        continue;
      }
      if (v.log_time < info.message_start_time || v.log_time > info.message_end_time) {
        problem(pos, "Chunk: message log time " + std::to_string(v.log_time) + " outside the chunk's range");
      }
      last_chunk_[offset] = {v.channel_id, v.log_time};
      ++info.message_count;
      message(v);
    }
    last_chunk_ok_ = true;
    last_chunk_at_ = pos;
    r_.chunks.push_back(info);
    index_length_after_[pos] = 0;
  }

  void message_index(std::uint64_t pos, FieldReader& f, std::size_t end) {
    if (!last_chunk_ok_) return;  // the chunk it indexes was not read: nothing to check against
    index_length_after_[last_chunk_at_] += end - pos;
    message_index_at_[pos] = f.u16();
    const std::uint16_t channel = message_index_at_[pos];
    const std::uint32_t array_bytes = f.u32();
    FieldReader a(f.skip(array_bytes), array_bytes);
    while (a.remaining() > 0) {
      const std::uint64_t time = a.u64();
      const std::uint64_t offset = a.u64();
      auto it = last_chunk_.find(static_cast<std::size_t>(offset));
      if (it == last_chunk_.end() || it->second.first != channel || it->second.second != time) {
        problem(pos, "Message Index of channel " + std::to_string(channel) + ": entry (" + std::to_string(time) + ", " +
                         std::to_string(offset) + ") names no such message in the chunk at byte " +
                         std::to_string(last_chunk_at_));
        return;
      }
    }
  }

  void finish() {
    for (auto& [id, s] : schemas_) r_.schemas.push_back(s);
    for (auto& [id, c] : channels_) r_.channels.push_back(c);
    r_.counted.schema_count = static_cast<std::uint16_t>(schemas_.size());
    r_.counted.channel_count = static_cast<std::uint32_t>(channels_.size());
    r_.counted.chunk_count = static_cast<std::uint32_t>(r_.chunks.size());
    if (!r_.footer_present) return;

    // The footer's summary must be where the Data End left off, and its CRC must match.
    const std::uint64_t footer_crc_end = footer_at_ + kRecordPrefixSize + 16;
    if (footer_summary_start_ == 0) {
      if (r_.summary_statistics || !chunk_indexes_.empty()) problem(footer_at_, "Footer says no summary, but there is one");
      return;
    }
    if (data_end_ == 0 || footer_summary_start_ != data_end_) {
      problem(footer_at_, "Footer's summary start " + std::to_string(footer_summary_start_) +
                              " is not the end of the Data End record (" + std::to_string(data_end_) + ")");
      return;
    }
    if (footer_summary_crc_ != 0) {
      const std::uint32_t crc = crc32(file_.data() + footer_summary_start_,
                                      static_cast<std::size_t>(footer_crc_end - footer_summary_start_));
      if (crc != footer_summary_crc_) {
        problem(footer_at_, "summary CRC mismatch (Footer says " + std::to_string(footer_summary_crc_) +
                                ", bytes give " + std::to_string(crc) + ")");
        return;
      }
    }
    if (footer_summary_offset_start_ != 0 &&
        (footer_summary_offset_start_ < footer_summary_start_ || footer_summary_offset_start_ > footer_at_)) {
      problem(footer_at_, "Footer's summary offset start " + std::to_string(footer_summary_offset_start_) +
                              " is outside the summary");
    }
    r_.summary_present = true;
    check_summary();
  }

  /// The summary must describe what was read: statistics, chunk indexes, schemas and channels.
  void check_summary() {
    const std::uint64_t at = footer_summary_start_;
    for (const auto& [id, s] : schemas_) {
      if (summary_schemas_.count(id) == 0) problem(at, "summary lacks Schema " + std::to_string(id));
    }
    for (const auto& [id, c] : channels_) {
      if (summary_channels_.count(id) == 0) problem(at, "summary lacks Channel " + std::to_string(id) + " (" + c.topic + ")");
    }
    if (r_.summary_statistics) {
      const Statistics& s = *r_.summary_statistics;
      const Statistics& c = r_.counted;
      auto differs = [&](const char* what, std::uint64_t stated, std::uint64_t counted) {
        if (stated != counted) {
          problem(at, std::string("Statistics ") + what + " " + std::to_string(stated) + ", the file holds " +
                          std::to_string(counted));
        }
      };
      differs("message_count", s.message_count, c.message_count);
      differs("schema_count", s.schema_count, c.schema_count);
      differs("channel_count", s.channel_count, c.channel_count);
      differs("chunk_count", s.chunk_count, c.chunk_count);
      differs("message_start_time", s.message_start_time, c.message_start_time);
      differs("message_end_time", s.message_end_time, c.message_end_time);
      std::set<std::uint16_t> ids;
      for (const auto& [id, n] : s.channel_message_counts) ids.insert(id);
      for (const auto& [id, n] : c.channel_message_counts) ids.insert(id);
      for (std::uint16_t id : ids) {
        const auto stated = s.channel_message_counts.find(id);
        const auto counted = c.channel_message_counts.find(id);
        differs(("channel_message_counts[" + std::to_string(id) + "]").c_str(),
                stated == s.channel_message_counts.end() ? 0 : stated->second,
                counted == c.channel_message_counts.end() ? 0 : counted->second);
      }
    }
    if (chunk_indexes_.size() != r_.chunks.size()) {
      problem(at, std::to_string(chunk_indexes_.size()) + " Chunk Index records for " + std::to_string(r_.chunks.size()) +
                      " chunks read");
      return;
    }
    for (std::size_t i = 0; i < chunk_indexes_.size(); ++i) {
      const ChunkIndexEntry& e = chunk_indexes_[i];
      const ChunkInfo& c = r_.chunks[i];
      if (e.info.offset != c.offset || e.info.length != c.length || e.info.compression != c.compression ||
          e.info.compressed_size != c.compressed_size || e.info.uncompressed_size != c.uncompressed_size ||
          e.info.message_start_time != c.message_start_time || e.info.message_end_time != c.message_end_time) {
        problem(e.offset, "Chunk Index disagrees with the chunk at byte " + std::to_string(c.offset));
        continue;
      }
      if (e.message_index_length != index_length_after_[c.offset]) {
        problem(e.offset, "Chunk Index says " + std::to_string(e.message_index_length) +
                              " bytes of Message Index after the chunk at byte " + std::to_string(c.offset) + ", there are " +
                              std::to_string(index_length_after_[c.offset]));
      }
      for (const auto& [channel, offset] : e.message_index_offsets) {
        const auto it = message_index_at_.find(offset);
        if (it == message_index_at_.end() || it->second != channel) {
          problem(e.offset, "Chunk Index: no Message Index of channel " + std::to_string(channel) + " at byte " +
                                std::to_string(offset));
        }
      }
    }
  }

  const MappedFile& file_;
  ReadReport& r_;
  OnDamage mode_;
  const std::function<void(const MessageView&)>& on_message_;

  std::map<std::uint16_t, SchemaInfo> schemas_;
  std::map<std::uint16_t, ChannelInfo> channels_;
  std::set<std::uint16_t> summary_schemas_, summary_channels_;
  std::string buffer_;  // the current chunk, decompressed
  std::map<std::size_t, std::pair<std::uint16_t, std::uint64_t>> last_chunk_;  // offset -> (channel, log time)
  bool last_chunk_ok_ = false;
  std::uint64_t last_chunk_at_ = 0;
  std::map<std::uint64_t, std::uint64_t> index_length_after_;  // chunk offset -> message index bytes after it
  std::map<std::uint64_t, std::uint16_t> message_index_at_;    // Message Index offset -> channel
  std::vector<ChunkIndexEntry> chunk_indexes_;
  bool in_summary_ = false;
  std::uint64_t data_end_ = 0;
  std::uint64_t footer_at_ = 0, footer_summary_start_ = 0, footer_summary_offset_start_ = 0;
  std::uint32_t footer_summary_crc_ = 0;
};

}  // namespace

std::string with_thousands(std::uint64_t n) {
  std::string digits = std::to_string(n);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out.push_back(',');
    out.push_back(digits[i]);
  }
  return out;
}

std::string ReadReport::recovery() const {
  if (!truncated_at) return "";
  return "truncated at byte " + std::to_string(*truncated_at) + ": " + with_thousands(chunks.size()) +
         (chunks.size() == 1 ? " complete chunk, " : " complete chunks, ") + with_thousands(counted.message_count) +
         (counted.message_count == 1 ? " message" : " messages") + " recovered; summary missing";
}

ReadReport scan_mcap(const std::string& path, OnDamage on_damage,
                     const std::function<void(const MessageView&)>& on_message) {
  const MappedFile file(path);
  ReadReport report;
  report.path = path;
  report.file_size = file.size();
  Scanner(file, report, on_damage, on_message).run();
  return report;
}

McapContents read_mcap(const std::string& path, OnDamage on_damage) {
  McapContents contents;
  contents.report = scan_mcap(path, on_damage, [&](const MessageView& v) {
    contents.messages.push_back({v.channel_id, v.sequence, v.log_time, v.publish_time,
                                 std::vector<std::uint8_t>(v.data, v.data + v.size)});
  });
  std::stable_sort(contents.messages.begin(), contents.messages.end(),
                   [](const Message& a, const Message& b) { return a.log_time < b.log_time; });
  return contents;
}

}  // namespace robodds::mcap
