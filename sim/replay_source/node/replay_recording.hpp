#pragma once
// Reading a recording to replay it, shared by `robodds replay` (real time) and the replay_source
// component (lockstep): the file with its damage turned into one error line, and each channel
// checked to carry one of our topics with its own schema.

#include <string>

#include "runtime/mcap/mcap_reader.hpp"
#include "runtime/topics/topic_catalog.hpp"

namespace robodds::replay_source {

/// Every message of `path` in log-time order (runtime/mcap's reader, recovering a truncated file:
/// report.truncated_at says so). ConfigError, one line, for a file with nothing readable (missing,
/// not MCAP) or a damaged one (its first problem: "FILE: byte N: reason").
mcap::McapContents read_recording(const std::string& path);

/// The catalog topic `channel` of `path` carries. ConfigError, one line naming the file, the
/// channel, its schema and why, unless the topic is in the catalog, its schema is the omgidl one
/// of the topic's type (idl_schema_name()) and its messages are cdr: "a schema that is not ours".
/// `hint` ends the line (e.g. how to leave the channel out).
const TopicInfo& replayable_topic(const std::string& path, const mcap::ReadReport& report, const mcap::ChannelInfo& channel,
                                  const std::string& hint);

}  // namespace robodds::replay_source
