// README.md's Layout against the code: its generated rows against the registered components and
// metrics modules, and its rows against the folders of the source tree (source_folders.hpp says
// which folders must have one).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/generated_block.hpp"
#include "common/line_diff.hpp"
#include "tools/regenerate/layout_table.hpp"
#include "tools/regenerate/readme_layout.hpp"
#include "tools/regenerate/registered_layout_table.hpp"
#include "tools/regenerate/source_folders.hpp"

namespace robodds {
namespace {

const std::string kReadmePath = std::string(ROBODDS_SOURCE_DIR) + "/README.md";

std::string readme() {
  std::ifstream in(kReadmePath);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(LayoutDoc, GeneratedRowsMatchTheRegisteredComponentsAndMetricsModules) {
  const std::string doc = readme();
  ASSERT_FALSE(doc.empty()) << "cannot read " << kReadmePath;
  const std::string in_doc = generated_block(doc, kLayoutTableMarkers, kReadmePath);
  const std::string rendered = render_registered_layout_table();
  // Not EXPECT_EQ: its dump of both tables would bury the diff.
  EXPECT_TRUE(in_doc == rendered) << "README.md's generated layout rows differ from the registration of the "
                                  << "components and metrics modules (- README, + registered):\n"
                                  << line_diff(in_doc, rendered)
                                  << "Regenerate them with scripts/regenerate_layout_doc.sh";
}

TEST(LayoutDoc, EveryFolderHoldingCodeHasARowAndEveryRowAFolder) {
  const std::string doc = readme();
  ASSERT_FALSE(doc.empty()) << "cannot read " << kReadmePath;
  const std::vector<LayoutRow> rows = layout_rows(doc);
  ASSERT_FALSE(rows.empty()) << "no row in README.md's section '## Layout'";
  std::string problems;
  for (const std::string& problem : layout_problems(rows, folders_holding_code(ROBODDS_SOURCE_DIR), ROBODDS_SOURCE_DIR)) {
    problems += "  " + problem + "\n";
  }
  EXPECT_TRUE(problems.empty()) << "README.md's Layout and the source tree disagree:\n"
                          << problems
                          << "Add or fix a hand-written row (a subfolder may instead be named as `<name>/` in its "
                             "parent's row); rows of component folders and metrics modules come from "
                             "scripts/regenerate_layout_doc.sh";
}

}  // namespace
}  // namespace robodds
