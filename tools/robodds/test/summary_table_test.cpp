#include "tools/robodds/summary_table.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace robodds {
namespace {

std::string dir_with_summary(const std::string& text) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string dir = ::testing::TempDir() + "summary_table." + info->name();
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/summary.json") << text;
  return dir;
}

TEST(SummaryTable, NestedKeysGetDottedPaths) {
  const std::string dir = dir_with_summary(R"({
  "scenario": "plant_smoke",
  "steps": 2001,
  "metrics": {
    "robots": {
      "1": {
        "final_x_m": 1.5,
        "pf_rmse_m": null
      }
    },
    "samples": {}
  },
  "run": {
    "deploy": "colocated",
    "ticks_per_s": 34263.7
  }
}
)");
  const std::string pad = std::string(48, ' ');
  auto row = [&](const std::string& key, const std::string& value) {
    return "  " + key + pad.substr(key.size()) + " " + value + "\n";
  };
  EXPECT_EQ(summary_table(dir), "\nsummary (" + dir + "/summary.json)\n" + row("scenario", "\"plant_smoke\"") +
                                    row("steps", "2001") + row("metrics.robots.1.final_x_m", "1.5") +
                                    row("metrics.robots.1.pf_rmse_m", "null") + row("metrics.samples", "{}") +
                                    row("run.deploy", "\"colocated\"") + row("run.ticks_per_s", "34263.7"));
}

TEST(SummaryTable, ReadsJsonNotLines) {
  // All on one line: a line-by-line reader sees nothing here.
  const std::string dir = dir_with_summary(R"({"a": {"b": 1, "c": [1, 2]}, "d": "x"})");
  const std::string table = summary_table(dir);
  EXPECT_NE(table.find("  a.b "), std::string::npos) << table;
  EXPECT_NE(table.find(" [1, 2]\n"), std::string::npos) << table;
  EXPECT_NE(table.find("  d "), std::string::npos) << table;
}

TEST(SummaryTable, MissingAndBrokenFilesGiveANote) {
  EXPECT_EQ(summary_table("/nonexistent/run"), "(no summary.json in /nonexistent/run: the scenario has no evaluator)\n");
  const std::string dir = dir_with_summary("{\"a\": [1, 2");
  EXPECT_NE(summary_table(dir).find("summary.json is not valid JSON"), std::string::npos) << summary_table(dir);
}

}  // namespace
}  // namespace robodds
