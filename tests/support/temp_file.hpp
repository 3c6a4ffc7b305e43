#pragma once
// Test-only helper for unit tests that need a file on disk.
//
// ctest runs every GoogleTest case as its own process and, with -j, several at once, so a
// fixed name under TempDir() is shared by concurrent cases (one case's scenario was once read
// by another). The path made here carries the running case's suite and name, so no two cases
// share a file and a rerun overwrites its own.

#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace robodds::test_support {

// Writes `text` to a file that ends in `name` and belongs to the running test case alone;
// returns its path.
inline std::string write_test_file(const std::string& name, const std::string& text) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string owner = info == nullptr ? std::string("no_test")
                                      : std::string(info->test_suite_name()) + "." + info->name();
  for (char& c : owner) {
    if (c == '/') c = '_';  // parameterised cases are named "Instance/Suite.Test/0"
  }
  const std::string path = ::testing::TempDir() + owner + "." + name;
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) ADD_FAILURE() << "could not write test file " << path;
  return path;
}

}  // namespace robodds::test_support
