#pragma once
// The main of a generator that rewrites one generated block of a checked-in document
// (docs/topics.md's topic table, README.md's layout rows): read, replace between the markers,
// write only when something changed, say which.

#include <functional>
#include <string>

#include "common/generated_block.hpp"

namespace robodds {

/// What one generator rewrites, for its messages.
struct GeneratedBlockJob {
  std::string program;  // "regenerate_topics_doc": prefixes its errors
  std::string block;    // "topic table": "<doc>: topic table up to date"
  std::string source;   // "the catalog": "<doc>: topic table regenerated from the catalog"
  BlockMarkers markers;
  std::function<std::string()> render;  // the block as it must read now
};

/// `program DOC`: rewrites DOC's block from job.render(). Returns the exit code: 0 done (or
/// already up to date), 1 an error (said on stderr), 2 bad usage.
int generated_block_main(int argc, char** argv, const GeneratedBlockJob& job);

}  // namespace robodds
