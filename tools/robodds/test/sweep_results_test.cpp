#include "tools/robodds/sweep_results.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace robodds::sweep {
namespace {

RunOutcome outcome(std::size_t index, std::size_t combination, std::uint64_t seed, bool ok,
                   std::vector<std::pair<std::string, double>> metrics, std::vector<std::string> sets = {}) {
  RunOutcome o;
  o.run = PlannedRun{index, combination, seed, std::move(sets)};
  o.ok = ok;
  o.exit_code = ok ? 0 : 1;
  o.wall_s = 1.5;
  o.error = ok ? "" : "exit 1: robodds: error: x, y";
  o.metrics = std::move(metrics);
  return o;
}

TEST(ReadMetrics, FiniteNumbersUnderMetricsOnly) {
  const std::string path = std::filesystem::temp_directory_path() / ("sweep_metrics_" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << R"({"status": "completed", "steps": 10, "metrics": {"waypoints_reached": 18, "rmse_m": 0.25,
    "robots": {"1": {"final_x_m": -3.5}}, "label": "x", "bad": null, "list": [1, 2], "quoted": "7"}})";
  const auto metrics = read_metrics(path);
  std::filesystem::remove(path);
  const std::vector<std::pair<std::string, double>> expected = {{"waypoints_reached", 18.0}, {"rmse_m", 0.25}, {"robots.1.final_x_m", -3.5}};
  EXPECT_EQ(metrics, expected);
}

TEST(Aggregate, PerCombinationOverSuccessfulRunsOnly) {
  const std::vector<RunOutcome> outcomes = {
      outcome(0, 0, 1, true, {{"a", 1.0}, {"b", 10.0}}), outcome(1, 0, 2, true, {{"a", 3.0}}),
      outcome(2, 0, 3, false, {{"a", 100.0}}),  // a failed run's metrics do not count
      outcome(3, 1, 1, true, {{"a", 5.0}, {"b", 6.0}}), outcome(4, 1, 2, true, {{"a", 7.0}, {"b", 8.0}})};
  const std::vector<MetricStats> rows = aggregate(outcomes);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].combination, 0u);
  EXPECT_EQ(rows[0].metric, "a");
  EXPECT_EQ(rows[0].summary.count, 2u);
  EXPECT_DOUBLE_EQ(rows[0].summary.mean, 2.0);
  EXPECT_DOUBLE_EQ(rows[0].summary.max, 3.0);
  EXPECT_EQ(rows[1].metric, "b");
  EXPECT_EQ(rows[1].summary.count, 1u);
  EXPECT_EQ(rows[3].combination, 1u);
  EXPECT_DOUBLE_EQ(rows[3].summary.mean, 7.0);
}

TEST(Tables, RunsCsvHasEveryRunAndQuotesErrors) {
  const std::vector<GridAxis> axes = {parse_grid_axis("c.eps=0.1,0.01")};
  const std::vector<RunOutcome> outcomes = {outcome(0, 0, 1, true, {{"a", 0.5}}, {"c.eps=0.1"}),
                                            outcome(1, 1, 1, false, {}, {"c.eps=0.01"})};
  EXPECT_EQ(runs_csv(axes, outcomes),
            "run,seed,c.eps,status,exit_code,wall_s,error,a\n"
            "0,1,0.1,ok,0,1.5,,0.5\n"
            "1,1,0.01,failed,1,1.5,\"exit 1: robodds: error: x, y\",\n");
}

TEST(Tables, SummaryCsvAndMarkdownRowPerCombinationAndMetric) {
  const std::vector<GridAxis> axes = {parse_grid_axis("c.eps=0.1,0.01")};
  const std::vector<RunOutcome> outcomes = {outcome(0, 0, 1, true, {{"a", 1.0}}, {"c.eps=0.1"}),
                                            outcome(1, 0, 2, true, {{"a", 3.0}}, {"c.eps=0.1"}),
                                            outcome(2, 1, 1, false, {}, {"c.eps=0.01"})};
  const std::vector<MetricStats> rows = aggregate(outcomes);
  const std::string csv = summary_csv(axes, rows);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "c.eps,metric,n,mean,std,min,max,ci95,never");
  EXPECT_NE(csv.find("\n0.1,a,2,2,1.4142135623730951,1,3,12.706"), std::string::npos) << csv;
  const std::string md = summary_markdown(axes, outcomes, rows);
  EXPECT_NE(md.find("## c.eps=0.1\n\n2 runs ok, 0 failed"), std::string::npos) << md;
  EXPECT_NE(md.find("## c.eps=0.01\n\n0 runs ok, 1 failed"), std::string::npos) << md;
  EXPECT_NE(md.find("| a | 2 | 2 | 12.71 | 1.414 | 1 | 3 | 0 |"), std::string::npos) << md;
}

TEST(Tables, OneRunHasNoSpread) {
  const std::vector<RunOutcome> outcomes = {outcome(0, 0, 1, true, {{"a", 1.5}})};
  const std::vector<MetricStats> rows = aggregate(outcomes);
  EXPECT_NE(summary_csv({}, rows).find("\na,1,1.5,,1.5,1.5,,0\n"), std::string::npos) << summary_csv({}, rows);
  EXPECT_NE(summary_markdown({}, outcomes, rows).find("| a | 1 | 1.5 | n/a | n/a | 1.5 | 1.5 | 0 |"), std::string::npos);
}

TEST(Aggregate, ATimeThatNeverCameIsCountedNotAveraged) {
  // time_to_final_s = -1: the robot never reached its last way-point. Averaged as a duration it
  // would pull the mean of 10 and 20 s down to 9.67 s.
  const std::vector<RunOutcome> outcomes = {
      outcome(0, 0, 1, true, {{"time_to_final_s", 10.0}, {"offset_m", -1.0}, {"robots.1.convergence_s", -1.0}}),
      outcome(1, 0, 2, true, {{"time_to_final_s", -1.0}, {"offset_m", 1.0}, {"robots.1.convergence_s", -1.0}}),
      outcome(2, 0, 3, true, {{"time_to_final_s", 20.0}, {"offset_m", 0.0}, {"robots.1.convergence_s", -1.0}})};
  const std::vector<MetricStats> rows = aggregate(outcomes);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].metric, "time_to_final_s");
  EXPECT_EQ(rows[0].summary.count, 2u);
  EXPECT_DOUBLE_EQ(rows[0].summary.mean, 15.0);
  EXPECT_DOUBLE_EQ(rows[0].summary.min, 10.0);
  EXPECT_EQ(rows[0].never, 1u);
  EXPECT_EQ(rows[1].metric, "offset_m") << "-1 of a metric that is not a time is a value";
  EXPECT_EQ(rows[1].summary.count, 3u);
  EXPECT_EQ(rows[1].never, 0u);
  EXPECT_EQ(rows[2].metric, "robots.1.convergence_s") << "every run never: still a row";
  EXPECT_EQ(rows[2].summary.count, 0u);
  EXPECT_EQ(rows[2].never, 3u);
  const std::string csv = summary_csv({}, rows);
  EXPECT_NE(csv.find("\ntime_to_final_s,2,15,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\nrobots.1.convergence_s,0,,,,,,3\n"), std::string::npos) << csv;
  const std::string md = summary_markdown({}, outcomes, rows);
  EXPECT_NE(md.find("| robots.1.convergence_s | 0 | n/a | n/a | n/a | n/a | n/a | 3 |"), std::string::npos) << md;
  EXPECT_TRUE(is_never("settle_time_s", -1.0));
  EXPECT_FALSE(is_never("settle_time_s", -0.5));
  EXPECT_FALSE(is_never("rmse_m", -1.0));
}

}  // namespace
}  // namespace robodds::sweep
