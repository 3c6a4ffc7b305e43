// The short report of `robodds run`: headline lines from summary.json, counts only when non-zero,
// at most 15 lines, numbers rounded.
#include "tools/robodds/run_report.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace robodds {
namespace {

std::vector<SummaryLeaf> leaves_of(const std::string& json) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string path = ::testing::TempDir() + "run_report." + info->name() + ".json";
  std::ofstream(path) << json;
  return summary_leaves(path);
}

const char* const kOneRobot = R"({
  "status": "completed",
  "steps": 35001,
  "step_s": 0.01,
  "metrics": {
    "robots": {"1": {"pf_rmse_m": 0.318504689672, "waypoints_reached": 18, "waypoints_total": 18, "time_to_final_s": 283.14}},
    "waypoints_reached": 18,
    "waypoints_total": 18,
    "time_to_final_s": 283.14,
    "time_to_valid_s": -1,
    "pf_rmse_m": 0.318504689672,
    "heading_rmse_deg": 3.46708539131,
    "phase1": {"settle_time_s": 404.3, "radius_rmse_m": 0.0394750960498},
    "phase2": {"settle_time_s": 303.08, "radius_rmse_m": 0.0359643310617},
    "stages": {"pf": {"position_error_m_mean": 0.293653154166}, "uwb": {"position_error_m_mean": 0.577664018513}}
  },
  "run": {"wall_time_s": 1.791097},
  "hosts": {"colocated": {"ticks": 35001, "missed_steps": 0, "late_steps": 0, "undecodable": {}}},
  "inputs": {
    "plant": {"plant/cmd": {"accepted": 35001, "rejected": {}, "adjusted": {"acceleration_limited": 1539, "saturated": 2953}}},
    "estimator": {"sensor/position": {"accepted": 3501, "rejected": {}, "adjusted": {}}}
  }
}
)";

const evaluator::Headline kHeadline = {
    {"way-points", "", "{waypoints_reached} of {waypoints_total} reached, time to the last: {time_to_final_s} s"},
    {"PF RMSE", "", "{pf_rmse_m} m position, {heading_rmse_deg:2} deg heading"},
    {"valid estimate", "", "time to it: {time_to_valid_s} s"},
    {"fix RMSE", "", "{measurement_rmse_m} m"},  // not recorded: left out
    {"{*}", "phase*", "settling: {settle_time_s} s, radius RMSE {radius_rmse_m} m"},
    {"stage {*}", "stages.*", "{position_error_m_mean:2} m"},
};

TEST(RunReport, RoundsToSignificantFiguresWithoutExponentOrTrailingZeros) {
  EXPECT_EQ(round_significant(283.14, 3), "283");
  EXPECT_EQ(round_significant(0.0063229, 3), "0.00632");
  EXPECT_EQ(round_significant(1.5, 3), "1.5");
  EXPECT_EQ(round_significant(0.0, 3), "0");
  EXPECT_EQ(round_significant(-2.0004, 3), "-2");
  EXPECT_EQ(round_significant(123456.0, 2), "123456");
  EXPECT_EQ(round_significant(0.099999, 2), "0.1");
}

TEST(RunReport, HeadlineLinesFillTheKeysOfTheTopLevelAndOfEachMatchedObject) {
  const std::vector<std::string> lines = headline_lines(kHeadline, leaves_of(kOneRobot));
  const std::vector<std::string> expected = {
      "  way-points        18 of 18 reached, time to the last: 283 s",
      "  PF RMSE           0.319 m position, 3.5 deg heading",
      "  valid estimate    time to it: never",
      "  phase1            settling: 404 s, radius RMSE 0.0395 m",
      "  phase2            settling: 303 s, radius RMSE 0.036 m",
      "  stage pf          0.29 m",
      "  stage uwb         0.58 m",
  };
  EXPECT_EQ(lines, expected);
  std::vector<std::string> used;
  headline_lines({kHeadline[1], kHeadline[5]}, leaves_of(kOneRobot), &used);
  EXPECT_EQ(used, (std::vector<std::string>{"metrics.pf_rmse_m", "metrics.heading_rmse_deg", "metrics.stages.pf.position_error_m_mean",
                                            "metrics.stages.uwb.position_error_m_mean"}));
}

TEST(RunReport, ShortReportHasStatusSpeedFiguresNonZeroCountsAndWhereTheOutputsAre) {
  RunReportInput in;
  in.summary = leaves_of(kOneRobot);
  in.headline = kHeadline;
  in.ticks = 35001;
  in.wall_s = 1.75;
  in.step_s = 0.01;
  in.out_dir = "out/paper1_waypoints";
  in.csv_files = 7;
  in.plot_files = 5;
  const std::vector<std::string> lines = run_report_lines(in);
  ASSERT_GE(lines.size(), 3U);
  EXPECT_EQ(lines.front(), "completed: 350 s simulated in 1.75 s (200x real time)");
  EXPECT_EQ(lines[lines.size() - 2], "  adjusted inputs   plant plant/cmd: 1539 acceleration_limited, 2953 saturated");
  EXPECT_EQ(lines.back(), "results: out/paper1_waypoints (summary.json, 7 CSV files, 5 plots; --verbose prints every figure)");
  for (const std::string& line : lines) {
    EXPECT_EQ(line.find("rejected"), std::string::npos) << "no rejected input, no line: " << line;
    EXPECT_EQ(line.find("warnings"), std::string::npos) << "no warning, no line: " << line;
    EXPECT_EQ(line.find("robots"), std::string::npos) << "a robot's figure twice: " << line;
  }
}

TEST(RunReport, FailedRunGivesItsReasonAndFiguresFromTheSummary) {
  RunReportInput in;
  in.summary = leaves_of(R"({"status": "failed", "reason": "estimator: stale", "steps": 1001, "step_s": 0.01,
    "run": {"wall_time_s": 0.5}, "hosts": {"h": {"missed_steps": 3, "undecodable": {"plant/cmd": 2}}, "g": {"reported": false}},
    "inputs": {"c": {"t/x": {"rejected": {"stale": 4}, "adjusted": {}}}}})");
  in.step_s = 0.01;
  in.warnings_logged = 1;
  in.out_dir = "o";
  const std::vector<std::string> lines = run_report_lines(in);
  const std::vector<std::string> expected = {
      "failed: 10 s simulated in 0.5 s (20x real time)",
      "  reason            estimator: stale",
      "  rejected inputs   c t/x: 4 stale",
      "  warnings          host h missed 3 real-time steps; host h: 2 undecodable samples (plant/cmd); host g did not report; +1 "
      "more in summary.json \"hosts\"",
      "results: o (summary.json, 0 CSV files; --verbose prints every figure)",
  };
  EXPECT_EQ(lines, expected);
}

TEST(RunReport, AtMostFifteenLinesHowEverManyFigures) {
  evaluator::Headline many;
  std::string metrics;
  for (int i = 0; i < 30; ++i) {
    many.push_back({"f" + std::to_string(i), "", "{k" + std::to_string(i) + "}"});
    metrics += std::string(i == 0 ? "" : ", ") + "\"k" + std::to_string(i) + "\": " + std::to_string(i);
  }
  RunReportInput in;
  in.summary = leaves_of(R"({"status": "degraded", "reason": "r", "metrics": {)" + metrics +
                         R"(}, "inputs": {"c": {"t": {"rejected": {"a": 1}, "adjusted": {"b": 1}}}}, "hosts": {"h": {"late_steps": 1}}})");
  in.headline = many;
  in.ticks = 10;
  in.step_s = 0.1;
  in.out_dir = "o";
  const std::vector<std::string> lines = run_report_lines(in);
  EXPECT_EQ(lines.size(), 15U);
  EXPECT_EQ(lines[2 + kMaxHeadlineLines - 1], "  (+22 more lines: --verbose, or summary.json)");
}

TEST(RunReport, AMissionThatFellShortSaysWhyAfterTheStatusAndTakesAFigureLine) {
  evaluator::Headline many;
  std::string metrics;
  for (int i = 0; i < 30; ++i) {
    many.push_back({"f" + std::to_string(i), "", "{k" + std::to_string(i) + "}"});
    metrics += std::string(i == 0 ? "" : ", ") + "\"k" + std::to_string(i) + "\": " + std::to_string(i);
  }
  RunReportInput in;
  in.summary = leaves_of(R"({"status": "degraded", "reason": "r", "mission": "incomplete: phase 1: formation never settled", )"
                         R"("metrics": {)" + metrics +
                         R"(}, "inputs": {"c": {"t": {"rejected": {"a": 1}, "adjusted": {"b": 1}}}}, "hosts": {"h": {"late_steps": 1}}})");
  in.headline = many;
  in.ticks = 10;
  in.step_s = 0.1;
  in.out_dir = "o";
  const std::vector<std::string> lines = run_report_lines(in);
  ASSERT_EQ(lines.size(), 15U) << "the mission line takes one of the figures' lines";
  EXPECT_EQ(lines[2], "  mission           incomplete: phase 1: formation never settled");
  EXPECT_EQ(lines[3 + kMaxHeadlineLines - 2], "  (+23 more lines: --verbose, or summary.json)");
}

TEST(RunReport, ACompleteMissionIsOneLineToo) {
  RunReportInput in;
  in.summary = leaves_of(R"({"status": "completed", "mission": "complete", "steps": 101, "step_s": 0.01})");
  in.step_s = 0.01;
  in.out_dir = "o";
  const std::vector<std::string> expected = {"completed: 1 s simulated", "  mission           complete",
                                             "results: o (summary.json, 0 CSV files; --verbose prints every figure)"};
  EXPECT_EQ(run_report_lines(in), expected);
}

TEST(RunReport, WithoutSummarySaysWhy) {
  RunReportInput in;
  in.summary_note = "no summary.json in o: the scenario has no evaluator";
  in.ticks = 101;
  in.step_s = 0.01;
  in.out_dir = "o";
  const std::vector<std::string> expected = {"done: 1 s simulated", "  (no summary.json in o: the scenario has no evaluator)",
                                             "results: o (0 CSV files; --verbose prints every figure)"};
  EXPECT_EQ(run_report_lines(in), expected);
}

}  // namespace
}  // namespace robodds
