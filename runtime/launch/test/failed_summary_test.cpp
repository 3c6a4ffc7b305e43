// After a failed run, summary.json says "status": "failed" and why, whoever wrote it first.
#include "runtime/launch/failed_summary.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/temp_file.hpp"

namespace robodds {
namespace {

const char* kEvaluatorSummary = "{\n  \"status\": \"completed\",\n  \"scenario\": \"s\",\n  \"metrics\": {\n    \"x\": 1\n  }\n}\n";

TEST(FailedSummary, WithoutASummaryTheStatusAndReasonAlone) {
  EXPECT_EQ(failed_summary_text("", "group 'sim' was killed"),
            "{\n  \"status\": \"failed\",\n  \"reason\": \"group 'sim' was killed\"\n}\n");
}

TEST(FailedSummary, ACompletedSummaryKeepsItsMetricsAndSaysFailed) {
  EXPECT_EQ(failed_summary_text(kEvaluatorSummary, "lockstep: no acknowledgement"),
            "{\n  \"status\": \"failed\",\n  \"reason\": \"lockstep: no acknowledgement\",\n  \"scenario\": \"s\",\n"
            "  \"metrics\": {\n    \"x\": 1\n  }\n}\n");
}

TEST(FailedSummary, TheRunnersReasonReplacesTheHosts) {
  const std::string host = "{\n  \"status\": \"failed\",\n  \"reason\": \"evaluation: interrupted by a \\\"signal\\\"\",\n  \"steps\": 3\n}\n";
  EXPECT_EQ(failed_summary_text(host, "group \"sim\" died"),
            "{\n  \"status\": \"failed\",\n  \"reason\": \"group \\\"sim\\\" died\",\n  \"steps\": 3\n}\n");
}

TEST(FailedSummary, SomethingElseIsReplaced) {
  EXPECT_EQ(failed_summary_text("not json", "r"), "{\n  \"status\": \"failed\",\n  \"reason\": \"r\"\n}\n");
}

TEST(FailedSummary, RecordFailedRunWritesTheFile) {
  const std::string dir = test_support::write_test_file("marker", "") + ".out";
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/summary.json";
  std::ofstream(file) << kEvaluatorSummary;
  record_failed_run(dir, "why");
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str().rfind("{\n  \"status\": \"failed\",\n  \"reason\": \"why\",\n  \"scenario\": \"s\"", 0), 0u) << text.str();
}

}  // namespace
}  // namespace robodds
