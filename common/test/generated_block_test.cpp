// The block between two marker lines: read, replaced, and a readable error without them.
#include "common/generated_block.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace robodds {
namespace {

const BlockMarkers kMarkers{"<!-- begin -->", "<!-- end -->"};

TEST(GeneratedBlock, ReplacesOnlyTheTextBetweenTheMarkers) {
  const std::string doc = "intro\n<!-- begin -->\nold\n<!-- end -->\noutro\n";
  EXPECT_EQ(generated_block(doc, kMarkers, "d.md"), "old\n");
  EXPECT_EQ(with_generated_block(doc, kMarkers, "new\nrows\n", "d.md"),
            "intro\n<!-- begin -->\nnew\nrows\n<!-- end -->\noutro\n");
}

TEST(GeneratedBlock, AnEmptyBlockIsABlock) {
  EXPECT_EQ(generated_block("<!-- begin -->\n<!-- end -->\n", kMarkers, "d.md"), "");
}

TEST(GeneratedBlock, AMissingOrMisplacedMarkerNamesTheDocAndTheMarkers) {
  for (const std::string doc : {"intro\n<!-- end -->\n", "<!-- begin -->\nno end\n", "<!-- end -->\n<!-- begin -->\n"}) {
    try {
      generated_block(doc, kMarkers, "README.md");
      FAIL() << "expected a MissingMarkerError for: " << doc;
    } catch (const MissingMarkerError& e) {
      EXPECT_THAT(e.what(), testing::StartsWith("README.md: expected the line '<!-- begin -->' followed later by '<!-- end -->'"));
    }
  }
}

}  // namespace
}  // namespace robodds
