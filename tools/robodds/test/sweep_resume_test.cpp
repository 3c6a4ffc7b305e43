#include "tools/robodds/sweep_resume.hpp"

#include <gtest/gtest.h>

namespace robodds::sweep {
namespace {

SweepSpec spec() {
  SweepSpec s;
  s.scenario_file = "scenario.yaml";
  s.source = "/work/s.yaml";
  s.seeds = "1-4";
  s.grid = {"c.eps=0.1,0.01"};
  s.run_args = {"--duration", "2"};
  return s;
}

TEST(MissingRuns, TheRunsWithoutAnOutcomeInPlanOrder) {
  const std::vector<PlannedRun> runs = plan_runs(parse_seeds("1-3"), {parse_grid_axis("c.eps=0.1,0.01")});
  ASSERT_EQ(runs.size(), 6u);
  const std::vector<PlannedRun> missing = missing_runs(runs, {0, 2, 3});
  ASSERT_EQ(missing.size(), 3u);
  EXPECT_EQ(missing[0].index, 1u);
  EXPECT_EQ(missing[1].index, 4u);
  EXPECT_EQ(missing[2].index, 5u);
  EXPECT_EQ(missing[2].seed, 3u);
  EXPECT_EQ(missing[2].sets, (std::vector<std::string>{"c.eps=0.01"}));
  EXPECT_TRUE(missing_runs(runs, {0, 1, 2, 3, 4, 5}).empty()) << "a complete sweep has nothing to resume";
  EXPECT_EQ(missing_runs(runs, {}).size(), 6u);
}

TEST(SpecDifference, NoneForTheSameSweep) { EXPECT_EQ(spec_difference(spec(), spec()), ""); }

TEST(SpecDifference, NamesTheFirstOptionThatDiffersWithBothValues) {
  SweepSpec given = spec();
  given.seeds = "1-6";
  EXPECT_EQ(spec_difference(spec(), given), "--seeds: '1-4' in sweep.json, '1-6' on the command line");
  given = spec();
  given.grid = {"c.eps=0.1"};
  EXPECT_EQ(spec_difference(spec(), given), "--set: 'c.eps=0.1,0.01' in sweep.json, 'c.eps=0.1' on the command line");
  given = spec();
  given.run_args = {};
  EXPECT_EQ(spec_difference(spec(), given), "the run options (--duration): '--duration 2' in sweep.json, '' on the command line");
  given = spec();
  given.source = "/work/other.yaml";
  EXPECT_EQ(spec_difference(spec(), given), "the scenario: '/work/s.yaml' in sweep.json, '/work/other.yaml' on the command line");
  given = spec();
  given.run_timeout_s = 60.0;
  EXPECT_EQ(spec_difference(spec(), given), "--run-timeout: '3600' in sweep.json, '60' on the command line");
}

}  // namespace
}  // namespace robodds::sweep
