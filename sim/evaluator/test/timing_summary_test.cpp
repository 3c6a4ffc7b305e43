// run.timing of summary.json: one entry per stage; a stage several components report (one
// estimator per robot) gets the largest median, p99 and max, the sum of their cycles and the
// component with the largest p99; ms rounded to us.
#include "sim/evaluator/node/timing_summary.hpp"

#include <gtest/gtest.h>

namespace robodds::evaluator {
namespace {

std::string section(const RunFigures& figures) {
  JsonWriter json;
  json.begin_object();
  write_timing_section(json, figures);
  json.end_object();
  return json.str();
}

TEST(TimingSummary, OneEntryPerStageWithTheWorstFiguresOfItsComponents) {
  RunFigures figures;
  HostHealth evaluation;
  evaluation.member = "evaluation";
  evaluation.timing.push_back({"estimator_robot1", {"window", 100, 2.0004, 7.0, 9.0}});
  evaluation.timing.push_back({"estimator_robot1", {"cycle", 100, 5.0, 11.0, 12.0}});
  HostHealth robot2;
  robot2.member = "robot2";
  robot2.timing.push_back({"estimator_robot2", {"window", 90, 1.5, 8.1234567, 8.5}});
  robot2.timing.push_back({"pf_robot2", {"pf", 10, 0.25, 0.5, 0.75}});
  figures.hosts = {evaluation, robot2};
  const std::string text = section(figures);
  EXPECT_EQ(text,
            "{\n"
            "  \"timing\": {\n"
            "    \"window\": {\n      \"cycle_ms_median\": 2,\n      \"cycle_ms_p99\": 8.123,\n"
            "      \"cycle_ms_max\": 9,\n      \"cycles\": 190,\n      \"component\": \"estimator_robot2\",\n"
            "      \"components\": 2\n    },\n"
            "    \"cycle\": {\n      \"cycle_ms_median\": 5,\n      \"cycle_ms_p99\": 11,\n"
            "      \"cycle_ms_max\": 12,\n      \"cycles\": 100,\n      \"component\": \"estimator_robot1\",\n"
            "      \"components\": 1\n    },\n"
            "    \"pf\": {\n      \"cycle_ms_median\": 0.25,\n      \"cycle_ms_p99\": 0.5,\n"
            "      \"cycle_ms_max\": 0.75,\n      \"cycles\": 10,\n      \"component\": \"pf_robot2\",\n"
            "      \"components\": 1\n    }\n"
            "  }\n"
            "}\n")
      << text;
}

TEST(TimingSummary, NoStageGivesAnEmptyObject) {
  RunFigures figures;
  figures.hosts.push_back(HostHealth{});
  EXPECT_EQ(section(figures), "{\n  \"timing\": {}\n}\n");
}

}  // namespace
}  // namespace robodds::evaluator
