#include "tools/robodds/sweep_plan.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace robodds::sweep {
namespace {

using Seeds = std::vector<std::uint64_t>;

TEST(ParseSeeds, RangesAndLists) {
  EXPECT_EQ(parse_seeds("1-5"), (Seeds{1, 2, 3, 4, 5}));
  EXPECT_EQ(parse_seeds("7"), (Seeds{7}));
  EXPECT_EQ(parse_seeds("0,3, 10-12"), (Seeds{0, 3, 10, 11, 12}));
  EXPECT_EQ(parse_seeds("18446744073709551615"), (Seeds{18446744073709551615ULL}));  // the largest
  EXPECT_THROW(parse_seeds("18446744073709551616"), std::invalid_argument);
}

TEST(ParseSeeds, BadTextNamesIt) {
  for (const char* bad : {"", "1-", "-3", "a", "1,,2", "5-3", "1-3,2", "1.5", "1 2"}) {
    try {
      parse_seeds(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("--seeds '") + bad + "'"), std::string::npos) << e.what();
    }
  }
}

TEST(ParseGridAxis, ValuesSplitOutsideBrackets) {
  const GridAxis a = parse_grid_axis("controller.epsilon_m=0.1, 0.01");
  EXPECT_EQ(a.key, "controller.epsilon_m");
  EXPECT_EQ(a.values, (std::vector<std::string>{"0.1", "0.01"}));
  const GridAxis b = parse_grid_axis("evaluator.topics=[a, b],[c]");
  EXPECT_EQ(b.values, (std::vector<std::string>{"[a, b]", "[c]"}));
}

TEST(ParseGridAxis, MalformedIsAnError) {
  for (const char* bad : {"epsilon=0.1", "controller.epsilon_m", ".k=1", "c.=1", "c.k=", "c.k=1,,2", "c.k=1,"}) {
    EXPECT_THROW(parse_grid_axis(bad), std::invalid_argument) << bad;
  }
}

TEST(PlanRuns, EveryCombinationTimesEverySeedLastAxisFastest) {
  const std::vector<GridAxis> axes = {parse_grid_axis("a.x=1,2"), parse_grid_axis("b.y=p,q,r")};
  EXPECT_EQ(combination_count(axes), 6u);
  EXPECT_EQ(combination_sets(axes, 0), (std::vector<std::string>{"a.x=1", "b.y=p"}));
  EXPECT_EQ(combination_sets(axes, 1), (std::vector<std::string>{"a.x=1", "b.y=q"}));
  EXPECT_EQ(combination_sets(axes, 5), (std::vector<std::string>{"a.x=2", "b.y=r"}));
  const std::vector<PlannedRun> runs = plan_runs({4, 9}, axes);
  ASSERT_EQ(runs.size(), 12u);
  EXPECT_EQ(runs[3].index, 3u);
  EXPECT_EQ(runs[3].combination, 1u);
  EXPECT_EQ(runs[3].seed, 9u);
  EXPECT_EQ(runs[3].sets, (std::vector<std::string>{"a.x=1", "b.y=q"}));
  EXPECT_EQ(plan_runs({1, 2, 3}, {}).size(), 3u);  // no grid: one combination
}

TEST(PlanRuns, OneKeyTwiceIsAnError) {
  EXPECT_THROW(plan_runs({1}, {parse_grid_axis("a.x=1"), parse_grid_axis("a.x=2")}), std::invalid_argument);
}

TEST(SweepSpec, JsonRoundTrip) {
  const SweepSpec spec{"scenario.yaml", "/abs/s.yaml", "1-3,7", {"controller.epsilon_m=0.1,0.01", "pf.list=[1, 2]"}, {"--duration", "50"}, 12.5};
  const std::string path = std::filesystem::temp_directory_path() / ("sweep_spec_test_" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << spec_json(spec);
  const SweepSpec back = read_spec(path);
  std::filesystem::remove(path);
  EXPECT_EQ(back.scenario_file, spec.scenario_file);
  EXPECT_EQ(back.source, spec.source);
  EXPECT_EQ(back.seeds, spec.seeds);
  EXPECT_EQ(back.grid, spec.grid);
  EXPECT_EQ(back.run_args, spec.run_args);
  EXPECT_EQ(back.run_timeout_s, 12.5);
  EXPECT_NE(spec_json(spec).find("\"runs\": 8"), std::string::npos) << spec_json(spec);
}

TEST(SweepSpec, NotASweepFileNamesFileAndKey) {
  const std::string path = std::filesystem::temp_directory_path() / ("sweep_spec_bad_" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << "{\"status\": \"completed\"}";
  try {
    read_spec(path);
    ADD_FAILURE() << "accepted a summary.json";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": robodds_sweep: missing"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace robodds::sweep
