#include "tools/regenerate/generated_block_main.hpp"

#include <cstdio>
#include <exception>
#include <fstream>
#include <iterator>

#include "common/replace_file.hpp"

namespace robodds {

int generated_block_main(int argc, char** argv, const GeneratedBlockJob& job) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DOC\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const auto fail = [&](const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\n", job.program.c_str(), message.c_str());
    return 1;
  };
  try {
    std::ifstream in(path);
    if (!in) {
      return fail(path + ": cannot read");
    }
    const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string updated = with_generated_block(doc, job.markers, job.render(), path);
    if (updated == doc) {
      std::printf("%s: %s up to date\n", path.c_str(), job.block.c_str());
      return 0;
    }
    // Whole or not at all: a generator stopped half-way must not leave half a README.
    const std::string error = replace_file(path, updated);
    if (!error.empty()) {
      return fail(error);
    }
    std::printf("%s: %s regenerated from %s\n", path.c_str(), job.block.c_str(), job.source.c_str());
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  return 0;
}

}  // namespace robodds
