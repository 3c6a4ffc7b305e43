// The share-dir lookup order: $ROBODDS_SHARE_DIR, then an installed tree next to the
// executable, then the source dir. The installed trees are real directories in a temp dir.
#include "runtime/config/share_dir.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace robodds {
namespace {

namespace fs = std::filesystem;

class ShareDirTest : public ::testing::Test {
 protected:
  // A directory of this test case alone (ctest runs cases concurrently).
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root_ = fs::path(::testing::TempDir()) / (std::string("share_dir_test.") + info->name());
    fs::remove_all(root_);
    fs::create_directories(root_ / "bin");
  }
  void TearDown() override { fs::remove_all(root_); }

  /// Creates <root>/share/robodds/<relative> (a small placeholder file).
  void add_installed_file(const std::string& relative) {
    const fs::path file = root_ / "share/robodds" / relative;
    fs::create_directories(file.parent_path());
    std::ofstream(file) << "<dds/>\n";
  }
  std::string executable() const { return (root_ / "bin/robodds").string(); }

  fs::path root_;
};

TEST_F(ShareDirTest, EnvironmentWinsOverAnInstalledTree) {
  add_installed_file(kShareDirMarker);
  EXPECT_EQ(find_share_dir("/elsewhere", executable(), "/src"), "/elsewhere");
}

TEST_F(ShareDirTest, InstalledTreeNextToTheExecutableWinsOverTheSourceDir) {
  add_installed_file(kShareDirMarker);
  EXPECT_EQ(find_share_dir(nullptr, executable(), "/src"), (root_ / "share/robodds").string());
}

TEST_F(ShareDirTest, EmptyEnvironmentValueCountsAsUnset) {
  add_installed_file(kShareDirMarker);
  EXPECT_EQ(find_share_dir("", executable(), "/src"), (root_ / "share/robodds").string());
}

TEST_F(ShareDirTest, ShareDirWithoutTheQosFileIsNotAnInstalledTree) {
  add_installed_file("deploy/qos/other.xml");  // a share/robodds without robodds_qos.xml
  EXPECT_EQ(find_share_dir(nullptr, executable(), "/src"), "/src");
}

TEST_F(ShareDirTest, BuildTreeBinaryUsesTheSourceDir) {
  EXPECT_EQ(find_share_dir(nullptr, executable(), "/src"), "/src");
}

TEST_F(ShareDirTest, UnknownExecutableUsesTheSourceDir) {
  EXPECT_EQ(find_share_dir(nullptr, "", "/src"), "/src");
}

TEST_F(ShareDirTest, ThisProcessIsABuildTreeBinary) {
  // The test binary lives in the build tree: no share/robodds next to it.
  ::unsetenv("ROBODDS_SHARE_DIR");
  EXPECT_EQ(share_dir_of_this_process("/src"), "/src");
  ::setenv("ROBODDS_SHARE_DIR", "/from/env", 1);
  EXPECT_EQ(share_dir_of_this_process("/src"), "/from/env");
  ::unsetenv("ROBODDS_SHARE_DIR");
}

}  // namespace
}  // namespace robodds
