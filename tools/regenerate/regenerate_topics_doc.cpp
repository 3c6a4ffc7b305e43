// regenerate_topics_doc DOC: rewrites the generated topic table of DOC (docs/topics.md) from the
// topic catalog. Run through scripts/regenerate_topics_doc.sh after changing the catalog.

#include "runtime/topics/topic_catalog.hpp"
#include "runtime/topics/topic_table.hpp"
#include "tools/regenerate/generated_block_main.hpp"

int main(int argc, char** argv) {
  return robodds::generated_block_main(
      argc, argv,
      {"regenerate_topics_doc", "topic table", "the catalog", {robodds::kTopicTableBegin, robodds::kTopicTableEnd},
       [] { return robodds::render_topic_table(robodds::topic_catalog()); }});
}
