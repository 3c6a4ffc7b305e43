#include "tools/cli/one_of.hpp"

#include <gtest/gtest.h>

namespace robodds::cli {
namespace {

/// The error of parsing `--deploy VALUE`, or "" when it parses.
std::string error_of(const std::string& value) {
  CLI::App app{"test", "robodds-test"};
  std::string deploy;
  app.add_option("--deploy", deploy)->check(one_of({"colocated", "processes"}));
  std::vector<std::string> args{"--deploy", value};
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  try {
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    return e.what();
  }
  return deploy == value ? "" : "(not stored)";
}

TEST(OneOf, TakesTheWordsAndNamesTheClosestOtherwise) {
  EXPECT_EQ(error_of("processes"), "");
  EXPECT_EQ(error_of("colocated"), "");
  EXPECT_EQ(error_of("proceses"), "--deploy: proceses not in {colocated,processes}; did you mean 'processes'?");
  EXPECT_EQ(error_of("everywhere"), "--deploy: everywhere not in {colocated,processes}");
}

}  // namespace
}  // namespace robodds::cli
