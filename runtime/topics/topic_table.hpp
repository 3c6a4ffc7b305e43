#pragma once
// The topic table of docs/topics.md, rendered from the topic catalog. The doc keeps the table
// between two marker comments; scripts/regenerate_topics_doc.sh rewrites it and
// runtime/topics/test/topic_table_test.cpp fails when the doc and the catalog differ.

#include <string>
#include <vector>

#include "runtime/topics/topic_catalog.hpp"

namespace robodds {

inline constexpr const char* kTopicTableBegin =
    "<!-- topic table: generated from the topic catalog (runtime/topics/topic_catalog.cpp, system/topics.cpp) by scripts/regenerate_topics_doc.sh; do not edit -->";
inline constexpr const char* kTopicTableEnd = "<!-- end of generated topic table -->";

/// The markdown table (header, separator, one row per topic in catalog order), each line ending
/// in '\n'.
std::string render_topic_table(const std::vector<TopicInfo>& topics);

/// The text between the marker lines of `doc` (without the markers). Throws ConfigError naming
/// `doc_name` if a marker is missing or they are out of order.
std::string generated_topic_table(const std::string& doc, const std::string& doc_name);

/// `doc` with the text between the marker lines replaced by `table`; ConfigError as above.
std::string with_generated_topic_table(const std::string& doc, const std::string& table, const std::string& doc_name);

}  // namespace robodds
