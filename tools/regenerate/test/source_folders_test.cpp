// Which folders README.md's Layout must list, on a small tree of its own.
#include "tools/regenerate/source_folders.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace robodds {
namespace {

namespace fs = std::filesystem;

class SourceFolders : public testing::Test {
 protected:
  void SetUp() override {
    // One folder per case: ctest runs the cases as parallel processes.
    root_ = fs::path(testing::TempDir()) / "source_folders_test" / testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(root_);
  }
  void TearDown() override { fs::remove_all(root_); }

  void file(const std::string& path) {
    fs::create_directories((root_ / path).parent_path());
    std::ofstream(root_ / path) << "x\n";
  }

  fs::path root_;
};

TEST_F(SourceFolders, AFolderWithACMakeListsOrSourcesAtItsTopHoldsCode) {
  file("CMakeLists.txt");
  file("common/angle.cpp");
  file("common/model/pose.hpp");
  file("scripts/build.sh");
  file("cmake/Helpers.cmake");
  file("idl/robodds.idl");
  file("deploy/docker/CMakeLists.txt");
  file("deploy/docker/Dockerfile");
  file("docs/readme.md");       // no code
  file("deploy/qos/qos.xml");  // no code
  EXPECT_EQ(folders_holding_code(root_), (std::vector<std::string>{"cmake/", "common/", "common/model/", "deploy/docker/",
                                                                    "idl/", "scripts/"}));
}

TEST_F(SourceFolders, AFolderWhoseOneFileIsItsCMakeListsOnlyAddsSubfolders) {
  file("components/CMakeLists.txt");
  file("components/plant/CMakeLists.txt");
  file("components/plant/plant.cpp");
  EXPECT_EQ(folders_holding_code(root_), (std::vector<std::string>{"components/plant/"}));
}

TEST_F(SourceFolders, SkipsHiddenFoldersBuildTreesAndTheConventionalPartsBelowTheTop) {
  file(".git/hooks/pre-commit.sh");
  file(".ci/run.sh");
  file("build/gen.cpp");
  file("build-release/gen.cpp");
  file("tests/build_graph/check.py");  // build* only at the top
  file("bench/run.sh");                // a top folder named bench is not a part of another
  file("sim/plant/plant.cpp");
  for (const char* part : {"test", "node", "config", "bench"}) {
    file(std::string("sim/plant/") + part + "/a.cpp");
    file(std::string("sim/plant/") + part + "/deeper/b.cpp");
  }
  EXPECT_EQ(folders_holding_code(root_),
            (std::vector<std::string>{"bench/", "sim/plant/", "tests/build_graph/"}));
}

}  // namespace
}  // namespace robodds
