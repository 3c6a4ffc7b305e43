#include "runtime/topics/topic_table.hpp"

#include <utility>

#include "runtime/base/error.hpp"

namespace robodds {
namespace {

std::string code(const std::string& text) { return "`" + text + "`"; }

/// "robodds::idl::SimTick" -> "SimTick".
std::string short_type_name(const std::string& type_name) {
  const std::size_t colons = type_name.rfind("::");
  return colons == std::string::npos ? type_name : type_name.substr(colons + 2);
}

std::string row(const TopicInfo& topic) {
  const std::string key = topic.key == "-" ? "— (unkeyed)" : code(topic.key);
  const std::string realtime = topic.qos_class == QosClass::kLockstep ? "— (lockstep only)" : code(to_string(topic.qos_class));
  const std::string lockstep = code(qos_profile_for(topic, TimeMode::kLockstep, false));
  return "| " + code(topic.name) + " | " + code(short_type_name(topic.type_name)) + " | " + key + " | " + realtime +
         " | " + lockstep + " | " + topic.producers + " | " + topic.consumers + " |\n";
}

/// Offsets of the first character after the begin marker's line and of the end marker.
std::pair<std::size_t, std::size_t> table_span(const std::string& doc, const std::string& doc_name) {
  const std::string begin_line = std::string(kTopicTableBegin) + "\n";
  const std::size_t begin = doc.find(begin_line);
  const std::size_t end = doc.find(kTopicTableEnd);
  if (begin == std::string::npos || end == std::string::npos || end < begin + begin_line.size()) {
    throw ConfigError(doc_name + ": expected the line '" + kTopicTableBegin + "' followed later by '" + kTopicTableEnd +
                      "' around the generated topic table");
  }
  return {begin + begin_line.size(), end};
}

}  // namespace

std::string render_topic_table(const std::vector<TopicInfo>& topics) {
  std::string table =
      "| Topic | IDL type | Key | Real time | Lockstep | Producers | Consumers |\n"
      "|---|---|---|---|---|---|---|\n";
  for (const TopicInfo& topic : topics) {
    table += row(topic);
  }
  return table;
}

std::string generated_topic_table(const std::string& doc, const std::string& doc_name) {
  const auto [begin, end] = table_span(doc, doc_name);
  return doc.substr(begin, end - begin);
}

std::string with_generated_topic_table(const std::string& doc, const std::string& table, const std::string& doc_name) {
  const auto [begin, end] = table_span(doc, doc_name);
  return doc.substr(0, begin) + table + doc.substr(end);
}

}  // namespace robodds
