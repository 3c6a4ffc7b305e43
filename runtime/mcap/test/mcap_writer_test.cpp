#include "runtime/mcap/mcap_writer.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <utility>
#include <vector>

#include "runtime/mcap/crc32.hpp"
#include "runtime/mcap/records.hpp"
#include "tests/support/temp_file.hpp"

namespace robodds::mcap {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

FieldReader at(const std::string& bytes, std::size_t offset) {
  return FieldReader(reinterpret_cast<const std::uint8_t*>(bytes.data()) + offset, bytes.size() - offset);
}

// The layout of a file without messages, byte by byte (https://mcap.dev/spec): this pins the
// record layouts independently of our reader.
TEST(McapWriter, EmptyFileHasTheSpecifiedLayout) {
  const std::string path = test_support::write_test_file("empty.mcap", "");
  Writer(path, WriterOptions{}).close();
  const std::string b = slurp(path);
  ASSERT_EQ(b.size(), 163U);
  EXPECT_EQ(b.substr(0, 8), std::string(kMagic, 8));
  EXPECT_EQ(b.substr(155), std::string(kMagic, 8));
  FieldReader header = at(b, 8);
  EXPECT_EQ(header.u8(), 0x01);
  EXPECT_EQ(header.u64(), 15U);
  EXPECT_EQ(header.str(), "");
  EXPECT_EQ(header.str(), "robodds");
  FieldReader data_end = at(b, 32);
  EXPECT_EQ(data_end.u8(), 0x0F);
  EXPECT_EQ(data_end.u64(), 4U);
  EXPECT_EQ(data_end.u32(), crc32(b.data(), 32));
  FieldReader stats = at(b, 45);
  EXPECT_EQ(stats.u8(), 0x0B);
  EXPECT_EQ(stats.u64(), 46U);
  EXPECT_EQ(stats.u64(), 0U);  // messages
  FieldReader offset = at(b, 100);
  EXPECT_EQ(offset.u8(), 0x0E);
  EXPECT_EQ(offset.u64(), 17U);
  EXPECT_EQ(offset.u8(), 0x0B);  // the Statistics group
  EXPECT_EQ(offset.u64(), 45U);
  EXPECT_EQ(offset.u64(), 55U);
  FieldReader footer = at(b, 126);
  EXPECT_EQ(footer.u8(), 0x02);
  EXPECT_EQ(footer.u64(), 20U);
  EXPECT_EQ(footer.u64(), 45U);   // summary start
  EXPECT_EQ(footer.u64(), 100U);  // summary offset start
  EXPECT_EQ(footer.u32(), crc32(b.data() + 45, 126 + 9 + 16 - 45));
}

TEST(McapWriter, ChunksReachTheFileAsSoonAsTheyAreFull) {
  const std::string path = test_support::write_test_file("chunks.mcap", "");
  WriterOptions options;
  options.compression = Compression::kNone;
  options.chunk_size_bytes = 1000;
  Writer writer(path, options);
  const std::uint16_t channel = writer.add_channel(0, "a", "raw");
  const std::uint64_t header_bytes = writer.file_bytes();
  const std::uint8_t payload[100] = {};
  writer.write(channel, 0, 1, 1, payload, sizeof payload);
  EXPECT_EQ(writer.file_bytes(), header_bytes);  // still in the open chunk
  for (std::uint32_t i = 1; i < 20; ++i) writer.write(channel, i, i, i, payload, sizeof payload);
  EXPECT_GT(writer.file_bytes(), header_bytes);
  EXPECT_EQ(slurp(path).size(), writer.file_bytes());  // on disk, not in a user-space buffer
  EXPECT_EQ(writer.message_count(), 20U);
  writer.close();
  writer.close();  // idempotent
  EXPECT_EQ(slurp(path).size(), writer.file_bytes());
}

// Each chunk's Message Index records list their channel's (log time, offset) pairs sorted by log
// time, stably, whether the messages came in order (the writer then skips the sort) or not; the
// records are read here straight from the file, not through our reader.
TEST(McapWriter, MessageIndexesAreSortedByLogTime) {
  const std::string path = test_support::write_test_file("index_order.mcap", "");
  WriterOptions options;
  options.compression = Compression::kNone;
  options.chunk_size_bytes = 1500;  // several chunks
  Writer writer(path, options);
  const std::uint16_t in_order = writer.add_channel(0, "in_order", "raw");
  const std::uint16_t shuffled = writer.add_channel(0, "shuffled", "raw");
  const std::uint8_t payload[40] = {};
  for (std::uint32_t i = 0; i < 60; ++i) {
    writer.write(in_order, i, 1000 + i / 2, 0, payload, sizeof payload);               // equal pairs: stable order
    writer.write(shuffled, i, 5000 + (i * 7) % 11 * 10 - i % 3, 0, payload, sizeof payload);  // back and forth
  }
  writer.close();
  const std::string bytes = slurp(path);
  std::size_t indexes = 0;
  for (std::size_t pos = kMagicSize; pos + kRecordPrefixSize <= bytes.size() - kMagicSize;) {
    FieldReader record = at(bytes, pos);
    const auto op = static_cast<Opcode>(record.u8());
    const std::uint64_t length = record.u64();
    if (op == Opcode::kMessageIndex) {
      const std::uint16_t channel = record.u16();
      const std::uint32_t array_bytes = record.u32();
      std::vector<std::pair<std::uint64_t, std::uint64_t>> entries;
      for (std::uint32_t n = 0; n < array_bytes / 16; ++n) {
        const std::uint64_t log_time = record.u64();  // two statements: the fields' order is fixed
        entries.emplace_back(log_time, record.u64());
      }
      ASSERT_FALSE(entries.empty());
      for (std::size_t k = 1; k < entries.size(); ++k) {
        EXPECT_LE(entries[k - 1].first, entries[k].first) << "channel " << channel << " at " << pos;
        if (entries[k - 1].first == entries[k].first) {
          EXPECT_LT(entries[k - 1].second, entries[k].second) << "stable";
        }
      }
      ++indexes;
    }
    if (op == Opcode::kFooter) break;
    pos += kRecordPrefixSize + length;
  }
  EXPECT_GE(indexes, 4U) << "two channels in at least two chunks";
}

TEST(McapWriter, RefusesBadOptionsIdsAndPathsWithOneLine) {
  WriterOptions options;
  options.chunk_size_bytes = 0;
  try {
    options.validate();
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("WriterOptions.chunk_size_bytes: 0 is outside", 0), 0U) << e.what();
  }
  try {
    Writer("/nonexistent-dir/x.mcap", WriterOptions{});
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent-dir/x.mcap: cannot create the MCAP file: No such file or directory");
  }
  const std::string path = test_support::write_test_file("ids.mcap", "");
  Writer writer(path, WriterOptions{});
  EXPECT_THROW(writer.add_channel(3, "t", "cdr"), McapError);
  EXPECT_EQ(writer.add_schema("s", "omgidl", "struct S {};"), 1);
  EXPECT_EQ(writer.add_channel(1, "t", "cdr"), 1);
  const std::uint8_t byte = 0;
  try {
    writer.write(2, 0, 0, 0, &byte, 1);
    FAIL();
  } catch (const McapError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": write: unknown channel id 2");
  }
  writer.close();
  EXPECT_THROW(writer.write(1, 0, 0, 0, &byte, 1), McapError);
}

}  // namespace
}  // namespace robodds::mcap
