#include "runtime/mcap/mcap_info.hpp"

#include <gtest/gtest.h>

namespace robodds::mcap {
namespace {

ReadReport two_channel_report() {
  ReadReport r;
  r.path = "run.mcap";
  r.file_size = 123456;
  r.library = "robodds";
  r.schemas = {{1, "robodds::msg::PlantState", "omgidl", "..."}};
  r.channels = {{1, 1, "plant/state", "cdr", {}}, {2, 0, "log", "", {}}};
  r.channel_counts[1] = {1001, 1000000000, 11000000000, 80000};  // 1001 messages over 10 s: 100 Hz
  r.channel_counts[2] = {1, 5000000000, 5000000000, 10};
  r.counted.message_count = 1002;
  r.counted.message_start_time = 1000000000;
  r.counted.message_end_time = 11000000000;
  r.chunks = {{8, 100, "zstd", 50, 200, 0, 0, 600}, {108, 100, "zstd", 40, 180, 0, 0, 402}};
  r.footer_present = true;
  r.summary_present = true;
  return r;
}

TEST(McapInfo, ValidFile) {
  EXPECT_EQ(format_info(two_channel_report()),
            "file:         run.mcap (123,456 bytes)\n"
            "library:      robodds\n"
            "summary:      present, CRCs valid (chunks, data section, summary)\n"
            "chunks:       2 (zstd), 90 bytes stored for 380 bytes of records\n"
            "messages:     1,002\n"
            "start:        1.000000000 s\n"
            "end:          11.000000000 s\n"
            "duration:     10.000 s\n"
            "channels:     2\n"
            "  id  topic        schema                    schema encoding  message encoding  messages  rate (Hz)\n"
            "   1  plant/state  robodds::msg::PlantState  omgidl           cdr                  1,001     100.00\n"
            "   2  log          (none)                    -                -                        1          -\n");
}

TEST(McapInfo, TruncatedFileSaysWhatWasRecovered) {
  ReadReport r = two_channel_report();
  r.footer_present = false;
  r.summary_present = false;
  r.truncated_at = 208;
  const std::string text = format_info(r);
  EXPECT_NE(text.find("summary:      missing\nrecovered:    truncated at byte 208: 2 complete chunks, 1,002 messages recovered; summary missing\n"),
            std::string::npos)
      << text;
}

TEST(McapInfo, ProblemsAreListedOneLineEach) {
  ReadReport r = two_channel_report();
  r.problems = {"run.mcap: byte 108: Chunk CRC mismatch (record says 1, records give 2)"};
  r.chunks[1].compression = "lz4";
  const std::string text = format_info(r);
  EXPECT_NE(text.find("summary:      present, 1 problem (below)\n"), std::string::npos) << text;
  EXPECT_NE(text.find("chunks:       2 (lz4 1, zstd 1)"), std::string::npos) << text;
  EXPECT_NE(text.find("problem:      run.mcap: byte 108: Chunk CRC mismatch (record says 1, records give 2)\n"),
            std::string::npos)
      << text;
}

TEST(McapInfo, RateNeedsTwoMessagesAtDistinctTimes) {
  EXPECT_EQ(channel_rate_hz({1, 5, 5, 0}), 0.0);
  EXPECT_EQ(channel_rate_hz({3, 5, 5, 0}), 0.0);
  EXPECT_DOUBLE_EQ(channel_rate_hz({11, 0, 1000000000, 0}), 10.0);
}

}  // namespace
}  // namespace robodds::mcap
