// Reading a recording for a replay (replay_recording.hpp): which channels are ours, and a damaged
// file as one line. Files written here with our MCAP writer.
#include "sim/replay_source/node/replay_recording.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "idl/idl_schema.hpp"
#include "runtime/base/error.hpp"
#include "runtime/mcap/mcap_writer.hpp"
#include "tests/support/temp_file.hpp"

namespace robodds::replay_source {
namespace {

const std::string kType = "robodds::idl::RobotState";

/// A file with one channel `topic` (schema `schema_name`/`schema_encoding`, `message_encoding`)
/// and one message; the problem replayable_topic() finds in it, or "" when it is ours.
std::string problem_of(const std::string& topic, const std::string& schema_name, const std::string& schema_encoding,
                       const std::string& message_encoding) {
  const std::string path = test_support::write_test_file("rec.mcap", "");
  {
    mcap::Writer writer(path, mcap::WriterOptions{});
    const auto schema = writer.add_schema(schema_name, schema_encoding, idl_schema_text(kType));
    const auto channel = writer.add_channel(schema, topic, message_encoding, {});
    const std::uint8_t payload[8] = {0, 1, 0, 0, 1, 0, 0, 0};
    writer.write(channel, 1, 1, 1, payload, sizeof payload);
    writer.close();
  }
  const mcap::McapContents contents = read_recording(path);
  try {
    const TopicInfo& info = replayable_topic("rec.mcap", contents.report, contents.report.channels.at(0), "hint");
    EXPECT_EQ(info.type_name, kType);
    return "";
  } catch (const ConfigError& e) {
    return e.what();
  }
}

TEST(ReplayableTopic, OurTopicWithItsSchemaIsOurs) { EXPECT_EQ(problem_of("plant/state", kType, "omgidl", "cdr"), ""); }

TEST(ReplayableTopic, EachWayOfNotBeingOursIsNamed) {
  EXPECT_EQ(problem_of("their/topic", kType, "omgidl", "cdr"),
            "rec.mcap: channel 'their/topic' has schema 'robodds::idl::RobotState' (omgidl), a schema that is not ours: "
            "'their/topic' is no robodds topic (`robodds record --list` lists them) (hint)");
  EXPECT_EQ(problem_of("plant/state", "robodds::idl::Odometry", "omgidl", "cdr"),
            "rec.mcap: channel 'plant/state' has schema 'robodds::idl::Odometry' (omgidl), a schema that is not ours: "
            "plant/state carries robodds::idl::RobotState as an omgidl schema with cdr messages (here cdr messages) (hint)");
  EXPECT_NE(problem_of("plant/state", kType, "ros2msg", "cdr").find("has schema 'robodds::idl::RobotState' (ros2msg), a schema that is not ours"),
            std::string::npos);
  EXPECT_NE(problem_of("plant/state", kType, "omgidl", "json").find("(here json messages)"), std::string::npos);
}

TEST(ReadRecording, ADamagedFileIsOneLineWithItsFirstProblem) {
  const std::string path = test_support::write_test_file("rec.mcap", "");
  {
    mcap::WriterOptions options;
    options.compression = mcap::Compression::kNone;
    mcap::Writer writer(path, options);
    const auto channel = writer.add_channel(0, "plant/state", "cdr", {});
    std::string payload(200, 'x');
    writer.write(channel, 1, 1, 1, reinterpret_cast<const std::uint8_t*>(payload.data()), payload.size());
    writer.close();
  }
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  bytes[bytes.find(std::string(200, 'x')) + 100] = 'y';  // inside the chunk: its CRC no longer matches
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  try {
    read_recording(path);
    FAIL() << "a damaged file was read";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path + ": byte "), std::string::npos) << what;
    EXPECT_NE(what.find("(the file is damaged; `robodds info " + path + "` lists every problem)"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line";
  }
}

}  // namespace
}  // namespace robodds::replay_source
