#include "runtime/launch/output_dir.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "runtime/base/error.hpp"

namespace robodds {
namespace {

/// The message of the ConfigError make_output_dir(dir) throws ("" if none).
std::string error_of(const std::string& dir) {
  try {
    make_output_dir(dir);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

std::string fresh_dir(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "output_dir_test_" + name;
  std::filesystem::remove_all(dir);
  return dir;
}

TEST(MakeOutputDir, CreatesTheDirectoryAndItsParentsAndLeavesNoProbe) {
  const std::string dir = fresh_dir("new") + "/a/b";
  EXPECT_EQ(error_of(dir), "");
  EXPECT_TRUE(std::filesystem::is_directory(dir));
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  EXPECT_EQ(error_of(dir), "");  // an existing directory is fine
}

TEST(MakeOutputDir, AnotherProcessProbingTheSameDirectoryWithOurPidDoesNotStopIt) {
  // Hosts in containers sharing one output volume have the same process ids: another one's probe
  // may be there, named as a pid-named probe of ours would be.
  const std::string dir = fresh_dir("shared");
  std::filesystem::create_directories(dir);
  const std::string others_probe = dir + "/.robodds-write-probe-" + std::to_string(::getpid());
  std::ofstream(others_probe) << "";
  EXPECT_EQ(error_of(dir), "");
  EXPECT_TRUE(std::filesystem::exists(others_probe)) << "not ours to remove";
  std::filesystem::remove(others_probe);
  EXPECT_TRUE(std::filesystem::is_empty(dir)) << "our own probe is gone";
}

TEST(MakeOutputDir, AFileOfThatNameIsNamed) {
  const std::string dir = fresh_dir("file");
  std::ofstream(dir) << "x";
  EXPECT_EQ(error_of(dir), dir + ": the output directory is not a directory (a file of that name exists)");
}

TEST(MakeOutputDir, ADirectoryBelowAFileIsNamed) {
  const std::string file = fresh_dir("parent");
  std::ofstream(file) << "x";
  const std::string message = error_of(file + "/below");
  EXPECT_EQ(message.rfind(file + "/below: cannot create the output directory: ", 0), 0u) << message;
}

TEST(MakeOutputDir, UncreatableAndUnwritableAreNamed) {
  // Tests may run as root, who writes into mode 0555 directories: /proc refuses everyone.
  EXPECT_EQ(error_of("/proc/robodds-out").rfind("/proc/robodds-out: cannot create the output directory: ", 0), 0u);
  EXPECT_EQ(error_of("/proc/self").rfind("/proc/self: the output directory is not writable: ", 0), 0u) << error_of("/proc/self");
}

}  // namespace
}  // namespace robodds
