// README.md's Layout rows read from the text and held against a small tree of their own.
#include "tools/regenerate/readme_layout.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace robodds {
namespace {

namespace fs = std::filesystem;

const char* const kReadme =
    "# robodds\n"
    "| `sim/scenarios/plant_smoke.yaml` | not in the Layout |\n"
    "## Layout\n"
    "Intro naming `common/`.\n"
    "| folder | what |\n"
    "|---|---|\n"
    "| `common/` | helpers |\n"
    "| `runtime/` | the runtime: `bus/` (buses), `io/` (inputs) |\n"
    "| `runtime/dds/` | Fast DDS |\n"
    "\n"
    "| component folder | type | executable | what |\n"
    "|---|---|---|---|\n"
    "| `sim/plant/` | `plant` | `robodds-plant` | the plant |\n"
    "\n"
    "| folder | what |\n"
    "|---|---|\n"
    "| `sim/plant/` | besides its generated row: `model/` the equations |\n"
    "## Documentation\n"
    "| `docs/` | not in the Layout |\n";

TEST(ReadmeLayout, ReadsTheRowsOfEveryTableOfTheLayoutSection) {
  const std::vector<LayoutRow> rows = layout_rows(kReadme);
  std::vector<std::string> folders;
  for (const LayoutRow& row : rows) {
    folders.push_back(row.folder);
  }
  EXPECT_EQ(folders, (std::vector<std::string>{"common/", "runtime/", "runtime/dds/", "sim/plant/", "sim/plant/"}));
  EXPECT_EQ(rows[1].text, "the runtime: `bus/` (buses), `io/` (inputs) |");
}

class ReadmeLayoutProblems : public testing::Test {
 protected:
  void SetUp() override {
    // One folder per case: ctest runs the cases as parallel processes.
    root_ = fs::path(testing::TempDir()) / "readme_layout_test" / testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(root_);
    for (const char* folder : {"common", "runtime/bus", "runtime/io", "runtime/dds", "sim/plant/model"}) {
      fs::create_directories(root_ / folder);
    }
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path root_;
};

TEST_F(ReadmeLayoutProblems, NoneWhenEveryFolderHasARowOrIsNamedByARowOfItsParent) {
  EXPECT_EQ(layout_problems(layout_rows(kReadme),
                            {"common/", "runtime/bus/", "runtime/dds/", "runtime/io/", "sim/plant/", "sim/plant/model/"}, root_),
            std::vector<std::string>{});
}

TEST_F(ReadmeLayoutProblems, AFolderWithoutRowAndAFolderThatIsNotThere) {
  fs::create_directories(root_ / "runtime/host");
  fs::create_directories(root_ / "tools/cli");
  fs::remove_all(root_ / "runtime/dds");
  EXPECT_EQ(layout_problems(layout_rows(kReadme), {"common/", "runtime/host/", "tools/", "tools/cli/"}, root_),
            (std::vector<std::string>{
                "`runtime/host/` holds code but has no row, and no row of `runtime/` names `host/`",
                "`tools/` holds code but has no row",
                "`tools/cli/` holds code but has no row, and no row of `tools/` names `cli/`",
                "`runtime/dds/` has a row but is no folder of the source tree",
            }));
}

}  // namespace
}  // namespace robodds
