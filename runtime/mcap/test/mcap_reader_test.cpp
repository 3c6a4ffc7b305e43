#include "runtime/mcap/mcap_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>

#include "runtime/mcap/mcap_writer.hpp"
#include "tests/support/temp_file.hpp"

namespace robodds::mcap {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void spit(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

struct Written {
  std::string path;
  std::vector<Message> messages;  // in write order
};

// `count` messages of 20-60 bytes on three channels (two with a schema), log times from `time_of`.
Written write_file(const std::string& name, Compression compression, std::size_t count, std::uint64_t chunk_size,
                   const std::function<std::uint64_t(std::size_t)>& time_of = [](std::size_t i) { return 1000 + 10 * i; }) {
  Written w{test_support::write_test_file(name, ""), {}};
  WriterOptions options;
  options.compression = compression;
  options.chunk_size_bytes = chunk_size;
  options.profile = "test";
  Writer writer(w.path, options);
  const std::uint16_t schema = writer.add_schema("pkg::Point", "omgidl", "module pkg { struct Point { double x; }; };");
  const std::uint16_t channels[3] = {writer.add_channel(schema, "a/point", "cdr", {{"k", "v"}}),
                                     writer.add_channel(schema, "b/point", "cdr"), writer.add_channel(0, "raw", "")};
  for (std::size_t i = 0; i < count; ++i) {
    Message m;
    m.channel_id = channels[i % 3];
    m.sequence = static_cast<std::uint32_t>(i);
    m.log_time = time_of(i);
    m.publish_time = m.log_time / 2;
    for (std::size_t k = 0; k < 20 + i % 41; ++k) m.data.push_back(static_cast<std::uint8_t>(i * 7 + k));
    writer.write(m.channel_id, m.sequence, m.log_time, m.publish_time, m.data.data(), m.data.size());
    w.messages.push_back(m);
  }
  writer.close();
  return w;
}

void expect_same(std::vector<Message> expected, const std::vector<Message>& got) {
  std::stable_sort(expected.begin(), expected.end(), [](const Message& a, const Message& b) { return a.log_time < b.log_time; });
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].channel_id, expected[i].channel_id) << i;
    EXPECT_EQ(got[i].sequence, expected[i].sequence) << i;
    EXPECT_EQ(got[i].log_time, expected[i].log_time) << i;
    EXPECT_EQ(got[i].publish_time, expected[i].publish_time) << i;
    EXPECT_EQ(got[i].data, expected[i].data) << i;
  }
}

class McapRoundTrip : public ::testing::TestWithParam<Compression> {};

TEST_P(McapRoundTrip, EveryMessageSchemaChannelAndStatisticComesBack) {
  const Written w = write_file("round.mcap", GetParam(), 1000, 4096);
  const McapContents c = read_mcap(w.path);
  const ReadReport& r = c.report;
  EXPECT_TRUE(r.valid());
  EXPECT_TRUE(r.summary_present);
  EXPECT_EQ(r.profile, "test");
  EXPECT_EQ(r.library, "robodds");
  ASSERT_EQ(r.schemas.size(), 1U);
  EXPECT_EQ(r.schemas[0].name, "pkg::Point");
  EXPECT_EQ(r.schemas[0].encoding, "omgidl");
  ASSERT_EQ(r.channels.size(), 3U);
  EXPECT_EQ(r.channels[0].topic, "a/point");
  EXPECT_EQ(r.channels[0].metadata.at("k"), "v");
  EXPECT_EQ(r.channels[2].schema_id, 0);
  expect_same(w.messages, c.messages);
  EXPECT_GT(r.chunks.size(), 5U);
  for (const ChunkInfo& chunk : r.chunks) EXPECT_EQ(chunk.compression, record_name(GetParam()));
  ASSERT_TRUE(r.summary_statistics);
  EXPECT_EQ(r.summary_statistics->message_count, 1000U);
  EXPECT_EQ(r.summary_statistics->chunk_count, r.chunks.size());
  EXPECT_EQ(r.summary_statistics->message_start_time, 1000U);
  EXPECT_EQ(r.summary_statistics->message_end_time, 1000U + 10 * 999);
  EXPECT_EQ(r.summary_statistics->channel_message_counts.at(1), 334U);
  EXPECT_EQ(r.summary_statistics->channel_message_counts.at(3), 333U);
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapRoundTrip,
                         ::testing::Values(Compression::kNone, Compression::kZstd, Compression::kLz4),
                         [](const auto& info) { return std::string(display_name(info.param)); });

TEST(McapReader, FileWithoutMessagesIsValid) {
  const Written w = write_file("empty.mcap", Compression::kZstd, 0, 1024);
  const McapContents c = read_mcap(w.path);
  EXPECT_TRUE(c.report.valid());
  EXPECT_TRUE(c.messages.empty());
  EXPECT_TRUE(c.report.chunks.empty());
  EXPECT_EQ(c.report.channels.size(), 3U);  // from the summary
  EXPECT_EQ(c.report.summary_statistics->message_count, 0U);
}

TEST(McapReader, ManySmallChunks) {
  const Written w = write_file("many.mcap", Compression::kLz4, 3000, 1);  // one message per chunk
  const McapContents c = read_mcap(w.path);
  EXPECT_TRUE(c.report.valid());
  EXPECT_EQ(c.report.chunks.size(), 3000U);
  expect_same(w.messages, c.messages);
}

TEST(McapReader, OutOfOrderLogTimesComeBackSorted) {
  // Times go back and forth within and across chunks (two writers' samples received late).
  const Written w = write_file("order.mcap", Compression::kZstd, 500, 2000,
                               [](std::size_t i) { return 100000 + (i * 7919) % 500 * 3 - (i % 4) * 1000; });
  const McapContents c = read_mcap(w.path);
  EXPECT_TRUE(c.report.valid()) << (c.report.problems.empty() ? "" : c.report.problems[0]);
  expect_same(w.messages, c.messages);
  EXPECT_TRUE(std::is_sorted(c.messages.begin(), c.messages.end(),
                             [](const Message& a, const Message& b) { return a.log_time < b.log_time; }));
  std::uint64_t lo = UINT64_MAX, hi = 0;
  for (const Message& m : w.messages) {
    lo = std::min(lo, m.log_time);
    hi = std::max(hi, m.log_time);
  }
  EXPECT_EQ(c.report.summary_statistics->message_start_time, lo);
  EXPECT_EQ(c.report.summary_statistics->message_end_time, hi);
}

TEST(McapReader, CorruptedChunkIsDetectedAndNamedWithItsOffset) {
  const Written w = write_file("crc.mcap", Compression::kNone, 300, 2000);
  const std::uint64_t second_chunk = read_mcap(w.path).report.chunks.at(1).offset;
  std::string bytes = slurp(w.path);
  bytes[second_chunk + 200] ^= 0x01;  // a payload byte inside the (uncompressed) chunk
  spit(w.path, bytes);
  try {
    read_mcap(w.path);
    FAIL() << "strict read accepted a corrupted chunk";
  } catch (const McapError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(w.path + ": byte " + std::to_string(second_chunk) + ": Chunk CRC mismatch", 0), 0U)
        << e.what();
  }
  const McapContents c = read_mcap(w.path, OnDamage::kRecover);
  EXPECT_FALSE(c.report.valid());
  EXPECT_FALSE(c.report.problems.empty());
  EXPECT_LT(c.messages.size(), 300U);  // the damaged chunk is left out...
  EXPECT_GT(c.messages.size(), 200U);  // ...the others are read
}

TEST(McapReader, CorruptedSummaryAndCompressedChunkAreDetected) {
  const Written w = write_file("summary.mcap", Compression::kZstd, 300, 2000);
  const std::string good = slurp(w.path);
  std::string bytes = good;
  bytes[bytes.size() - 60] ^= 0x40;  // inside the summary
  spit(w.path, bytes);
  EXPECT_THROW(read_mcap(w.path), McapError);
  const ReadReport recovered = read_mcap(w.path, OnDamage::kRecover).report;
  EXPECT_FALSE(recovered.valid());
  EXPECT_EQ(recovered.counted.message_count, 300U);  // the data section is intact

  bytes = good;
  bytes[100] ^= 0x10;  // inside the first (compressed) chunk
  spit(w.path, bytes);
  EXPECT_THROW(read_mcap(w.path), McapError);
}

TEST(McapReader, EditedStatisticsAreCaughtByTheSummaryCrc) {
  // A Statistics record whose message count is off by one: written by hand over a valid file.
  const Written w = write_file("stats.mcap", Compression::kNone, 10, 1 << 20);
  std::string bytes = slurp(w.path);
  std::size_t at = bytes.size();
  // The Statistics record is the one opcode 0x0B whose next 8 bytes are its length 46 + 2 + 10 * 10.
  for (std::size_t i = 0; i + 9 < bytes.size(); ++i) {
    if (bytes[i] == '\x0B' && static_cast<unsigned char>(bytes[i + 1]) == 46 + 10 * 3 && bytes[i + 2] == 0) at = i;
  }
  ASSERT_LT(at, bytes.size());
  bytes[at + 9] = static_cast<char>(bytes[at + 9] + 1);
  spit(w.path, bytes);
  const ReadReport r = read_mcap(w.path, OnDamage::kRecover).report;
  ASSERT_FALSE(r.problems.empty());
  // The summary CRC catches the edit first; the statistics check runs only on a CRC-valid summary.
  EXPECT_NE(r.problems[0].find("summary CRC mismatch"), std::string::npos) << r.problems[0];
}

TEST(McapReader, EveryTruncationRecoversTheCompleteChunksAndNeverCrashes) {
  const Written w = write_file("cut.mcap", Compression::kZstd, 400, 1500);
  const std::string whole = slurp(w.path);
  const ReadReport full = read_mcap(w.path).report;
  ASSERT_GT(full.chunks.size(), 10U);
  const std::string cut_path = w.path + ".cut";
  // Every cut point in the header and first chunk, then every 7th byte to the end.
  for (std::size_t cut = 0; cut < whole.size(); cut += (cut < 600 ? 1 : 7)) {
    spit(cut_path, whole.substr(0, cut));
    if (cut < 8) {
      EXPECT_THROW(read_mcap(cut_path, OnDamage::kRecover), McapError) << cut;
      continue;
    }
    EXPECT_THROW(read_mcap(cut_path), McapError) << cut;  // strict: a cut file is not valid
    const McapContents c = read_mcap(cut_path, OnDamage::kRecover);
    ASSERT_TRUE(c.report.truncated_at) << cut;
    EXPECT_LE(*c.report.truncated_at, cut);
    // Exactly the chunks that end before the cut.
    std::size_t complete = 0, messages = 0;
    for (const ChunkInfo& chunk : full.chunks) {
      if (chunk.offset + chunk.length <= cut) {
        ++complete;
        messages += chunk.message_count;
      }
    }
    ASSERT_EQ(c.report.chunks.size(), complete) << cut;
    ASSERT_EQ(c.messages.size(), messages) << cut;
    EXPECT_TRUE(c.report.problems.empty()) << cut << ": " << c.report.problems[0];
    EXPECT_NE(c.report.recovery().find("summary missing"), std::string::npos);
  }
}

TEST(McapReader, RecoveryLineSaysWhatWasRecovered) {
  const Written w = write_file("line.mcap", Compression::kLz4, 3456, 1 << 12);
  std::string bytes = slurp(w.path);
  const ReadReport full = read_mcap(w.path).report;
  const ChunkInfo& last = full.chunks.back();
  spit(w.path, bytes.substr(0, last.offset + 10));
  const ReadReport r = read_mcap(w.path, OnDamage::kRecover).report;
  EXPECT_EQ(r.recovery(), "truncated at byte " + std::to_string(last.offset) + ": " +
                              with_thousands(full.chunks.size() - 1) + " complete chunks, " +
                              with_thousands(3456 - last.message_count) + " messages recovered; summary missing");
}

TEST(McapReader, NotAnMcapOrMissingIsOneLine) {
  const std::string text = test_support::write_test_file("text.mcap", "hello, this is not an mcap file");
  try {
    read_mcap(text, OnDamage::kRecover);
    FAIL();
  } catch (const McapError& e) {
    EXPECT_EQ(std::string(e.what()), text + ": byte 0: not an MCAP file (bad magic)");
  }
  try {
    read_mcap("/nonexistent/x.mcap", OnDamage::kRecover);
    FAIL();
  } catch (const McapError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/x.mcap: cannot open: No such file or directory");
  }
}

TEST(McapReader, RecordOverrunningTheFileIsNamed) {
  const Written w = write_file("overrun.mcap", Compression::kNone, 50, 1 << 20);
  std::string bytes = slurp(w.path);
  bytes[8 + 1 + 7] = '\x7F';  // the Header's length: now far beyond the end
  spit(w.path, bytes);
  try {
    read_mcap(w.path);
    FAIL();
  } catch (const McapError& e) {
    EXPECT_NE(std::string(e.what()).find(": byte 8: truncated: Header record of "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("overruns the file"), std::string::npos) << e.what();
  }
}

TEST(McapReader, UnknownCompressionIsNamed) {
  const Written w = write_file("codec.mcap", Compression::kZstd, 5, 1 << 20);
  std::string bytes = slurp(w.path);
  const std::size_t at = bytes.find("zstd");
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, 4, "zzzz");
  spit(w.path, bytes);
  try {
    read_mcap(w.path);
    FAIL();
  } catch (const McapError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown compression 'zzzz'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace robodds::mcap
