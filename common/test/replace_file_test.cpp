#include "common/replace_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace robodds {
namespace {

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ReplaceFile, ReplacesTheWholeFileAndLeavesNoTemporary) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "robodds_replace_file_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "summary.json").string();
  EXPECT_EQ(replace_file(path, "first, longer text"), "");
  EXPECT_EQ(replace_file(path, "second"), "");
  EXPECT_EQ(read(path), "second");
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  std::filesystem::remove_all(dir);
}

TEST(ReplaceFile, ANonWritablePlaceIsOneLineNamingTheFile) {
  const std::string path = "/nonexistent-robodds-dir/summary.json";
  const std::string error = replace_file(path, "x");
  EXPECT_EQ(error, "cannot write " + path + ".tmp");
}

}  // namespace
}  // namespace robodds
