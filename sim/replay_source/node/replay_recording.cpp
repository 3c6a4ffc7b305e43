#include "sim/replay_source/node/replay_recording.hpp"

#include "idl/idl_schema.hpp"
#include "runtime/base/error.hpp"

namespace robodds::replay_source {

mcap::McapContents read_recording(const std::string& path) {
  mcap::McapContents contents = mcap::read_mcap(path, mcap::OnDamage::kRecover);
  if (!contents.report.problems.empty()) {
    throw ConfigError(contents.report.problems.front() + " (the file is damaged; `robodds info " + path +
                      "` lists every problem)");
  }
  return contents;
}

const TopicInfo& replayable_topic(const std::string& path, const mcap::ReadReport& report, const mcap::ChannelInfo& channel,
                                  const std::string& hint) {
  const mcap::SchemaInfo* schema = nullptr;
  for (const mcap::SchemaInfo& s : report.schemas) {
    if (s.id == channel.schema_id) schema = &s;
  }
  const std::string schema_text = schema == nullptr ? "none" : "'" + schema->name + "' (" + schema->encoding + ")";
  const auto not_ours = [&](const std::string& why) {
    return ConfigError(path + ": channel '" + channel.topic + "' has schema " + schema_text + ", a schema that is not ours: " +
                       why + " (" + hint + ")");
  };
  const TopicInfo* topic = find_topic(channel.topic);
  if (topic == nullptr) {
    throw not_ours("'" + channel.topic + "' is no robodds topic (`robodds record --list` lists them)");
  }
  if (schema == nullptr || schema->encoding != "omgidl" || schema->name != idl_schema_name(topic->type_name) ||
      channel.message_encoding != "cdr") {
    throw not_ours(channel.topic + " carries " + idl_schema_name(topic->type_name) + " as an omgidl schema with cdr messages (here " +
                   (channel.message_encoding.empty() ? std::string("no") : channel.message_encoding) + " messages)");
  }
  return *topic;
}

}  // namespace robodds::replay_source
