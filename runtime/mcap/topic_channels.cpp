#include "runtime/mcap/topic_channels.hpp"

#include <map>
#include <string>

#include "idl/idl_schema.hpp"

namespace robodds::mcap {

std::vector<std::uint16_t> add_topic_channels(Writer& writer, const std::vector<const TopicInfo*>& topics) {
  std::vector<std::uint16_t> channels;
  std::map<std::string, std::uint16_t> schemas;
  for (const TopicInfo* topic : topics) {
    auto it = schemas.find(topic->type_name);
    if (it == schemas.end()) {
      it = schemas.emplace(topic->type_name, writer.add_schema(idl_schema_name(topic->type_name), "omgidl",
                                                                idl_schema_text(topic->type_name)))
               .first;
    }
    // What a replay needs to publish it as the run did: the topic's real-time QoS profile and key.
    const std::map<std::string, std::string> metadata = {
        {"qos_profile", qos_profile_for(*topic, TimeMode::kRealtime, false)}, {"key", topic->key}};
    channels.push_back(writer.add_channel(it->second, topic->name, "cdr", metadata));
  }
  return channels;
}

}  // namespace robodds::mcap
