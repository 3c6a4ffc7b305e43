// regenerate_topics_doc DOC: rewrites the generated topic table of DOC (docs/topics.md) from the
// topic catalog. Run through scripts/regenerate_topics_doc.sh after changing the catalog.

#include <cstdio>
#include <exception>
#include <fstream>
#include <iterator>
#include <string>

#include "runtime/base/error.hpp"
#include "runtime/topics/topic_catalog.hpp"
#include "runtime/topics/topic_table.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s docs/topics.md\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  try {
    std::ifstream in(path);
    if (!in) {
      throw robodds::ConfigError(path + ": cannot read");
    }
    const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string updated =
        robodds::with_generated_topic_table(doc, robodds::render_topic_table(robodds::topic_catalog()), path);
    if (updated == doc) {
      std::printf("%s: topic table up to date\n", path.c_str());
      return 0;
    }
    std::ofstream out(path, std::ios::trunc);
    out << updated;
    if (!out.flush()) {
      throw robodds::ConfigError(path + ": cannot write");
    }
    std::printf("%s: topic table regenerated from the catalog\n", path.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "regenerate_topics_doc: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
