#pragma once
// MCAP record layouts (https://mcap.dev/spec, major version 0): opcodes, and the little-endian
// encoding of the field types the records use. Shared by the writer and the reader.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

namespace robodds::mcap {

/// 0x89 "MCAP" '0' "\r\n": the first and last eight bytes of every file.
inline constexpr char kMagic[8] = {'\x89', 'M', 'C', 'A', 'P', '0', '\r', '\n'};
inline constexpr std::size_t kMagicSize = 8;
/// Every record: opcode (1 byte) + content length (uint64).
inline constexpr std::size_t kRecordPrefixSize = 9;

enum class Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

/// Footer content: summary_start u64, summary_offset_start u64, summary_crc u32.
inline constexpr std::size_t kFooterContentSize = 20;
/// Data End content: data_section_crc u32.
inline constexpr std::size_t kDataEndContentSize = 4;

/// The summary's Statistics record (also what a reader counts itself).
struct Statistics {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0;
  std::uint32_t attachment_count = 0;
  std::uint32_t metadata_count = 0;
  std::uint32_t chunk_count = 0;
  std::uint64_t message_start_time = 0;  // ns, 0 when there is no message
  std::uint64_t message_end_time = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};

/// Appends little-endian fields to a byte buffer (std::string used as bytes).
class RecordBuilder {
 public:
  explicit RecordBuilder(std::string& out) : out_(out) {}
  void u8(std::uint8_t v) { out_.push_back(static_cast<char>(v)); }
  void u16(std::uint16_t v) { le(v, 2); }
  void u32(std::uint32_t v) { le(v, 4); }
  void u64(std::uint64_t v) { le(v, 8); }
  /// String: uint32 length + bytes (also the encoding of Bytes with a uint32 length).
  void str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    out_.append(s);
  }
  void raw(const void* data, std::size_t size) { out_.append(static_cast<const char*>(data), size); }
  /// Opens a record: opcode and a length patched by end_record().
  std::size_t begin_record(Opcode op) {
    u8(static_cast<std::uint8_t>(op));
    const std::size_t at = out_.size();
    u64(0);
    return at;
  }
  void end_record(std::size_t length_at) { patch_u64(length_at, out_.size() - length_at - 8); }
  /// Opens a uint32 byte-length prefix (maps and arrays); end_u32_length() patches it.
  std::size_t begin_u32_length() {
    const std::size_t at = out_.size();
    u32(0);
    return at;
  }
  void end_u32_length(std::size_t at) { patch(at, out_.size() - at - 4, 4); }
  void patch_u64(std::size_t at, std::uint64_t v) { patch(at, v, 8); }
  std::size_t size() const { return out_.size(); }

 private:
  // One append per field, not one push_back per byte: a recorder frames millions of fields.
  void le(std::uint64_t v, int bytes) {
    char b[8];
    for (int i = 0; i < bytes; ++i) b[i] = static_cast<char>((v >> (8 * i)) & 0xFFU);
    out_.append(b, static_cast<std::size_t>(bytes));
  }
  void patch(std::size_t at, std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) out_[at + static_cast<std::size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xFFU);
  }
  std::string& out_;
};

/// Reads little-endian fields from [data, data + size); every read is bounds-checked and throws
/// FieldOverrun (the reader turns it into a located McapError).
class FieldReader {
 public:
  struct FieldOverrun {
    std::size_t at;  // offset within the buffer where the field did not fit
  };
  FieldReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t u8() { return static_cast<std::uint8_t>(le(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(le(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(le(4)); }
  std::uint64_t u64() { return le(8); }
  std::string str() { return bytes(u32()); }
  std::string bytes(std::uint64_t n) {
    need(n);
    std::string s(reinterpret_cast<const char*>(data_ + pos_), static_cast<std::size_t>(n));
    pos_ += static_cast<std::size_t>(n);
    return s;
  }
  const std::uint8_t* skip(std::uint64_t n) {
    need(n);
    const std::uint8_t* p = data_ + pos_;
    pos_ += static_cast<std::size_t>(n);
    return p;
  }
  std::size_t pos() const { return pos_; }
  std::size_t remaining() const { return size_ - pos_; }

 private:
  void need(std::uint64_t n) const {
    if (n > size_ - pos_) throw FieldOverrun{pos_};
  }
  std::uint64_t le(int bytes) {
    need(static_cast<std::uint64_t>(bytes));
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= std::uint64_t{data_[pos_ + static_cast<std::size_t>(i)]} << (8 * i);
    pos_ += static_cast<std::size_t>(bytes);
    return v;
  }
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace robodds::mcap
