#include "common/line_diff.hpp"

#include <gtest/gtest.h>

namespace robodds {
namespace {

TEST(LineDiff, EqualTextsGiveNothing) { EXPECT_EQ(line_diff("a\nb\n", "a\nb\n"), ""); }

TEST(LineDiff, ChangedLineIsRemovedThenAdded) { EXPECT_EQ(line_diff("a\nb\nc\n", "a\nx\nc\n"), "- b\n+ x\n"); }

TEST(LineDiff, InsertionsAndDeletionsKeepTheCommonLines) {
  EXPECT_EQ(line_diff("a\nc\n", "a\nb\nc\n"), "+ b\n");
  EXPECT_EQ(line_diff("a\nb\nc\n", "c\n"), "- a\n- b\n");
  EXPECT_EQ(line_diff("", "x\n"), "+ x\n");
}

}  // namespace
}  // namespace robodds
