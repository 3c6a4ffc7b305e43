#include "sim/evaluator/node/health_summary.hpp"

#include <gtest/gtest.h>

namespace robodds::evaluator {
namespace {

std::string sections(const RunFigures& figures) {
  JsonWriter json;
  json.begin_object();
  write_health_sections(json, figures);
  json.end_object();
  return json.str();
}

TEST(HealthSummary, EveryHostAndEveryInputOfItsComponents) {
  RunFigures figures;
  HostHealth sim;
  sim.member = "sim";
  sim.figures.ticks = 1001;
  sim.figures.missed_steps = 416;
  sim.figures.late_steps = 30;
  sim.figures.worst_lateness_s = 0.1234567;
  InputCounts cmd;
  cmd.accepted = 998;
  cmd.rejected["non_finite"] = 3;
  cmd.adjusted["saturated"] = 2;
  sim.components.push_back({"plant", {{"plant/cmd", cmd}}});
  sim.components.push_back({"mission", {}});  // no inputs: not listed under "inputs"
  sim.undecodable["plant/cmd"] = 7;
  HostHealth eval;
  eval.member = "eval";
  eval.figures.ticks = 1001;
  eval.components.push_back({"evaluator", {{"plant/state", InputCounts{5, {}, {}}}}});
  figures.hosts = {eval, sim};
  figures.hosts_not_heard = {"control"};
  const std::string text = sections(figures);
  EXPECT_EQ(text,
            "{\n"
            "  \"hosts\": {\n"
            "    \"eval\": {\n      \"ticks\": 1001,\n      \"missed_steps\": 0,\n      \"late_steps\": 0,\n"
            "      \"worst_lateness_s\": 0,\n      \"undecodable\": {}\n    },\n"
            "    \"sim\": {\n      \"ticks\": 1001,\n      \"missed_steps\": 416,\n      \"late_steps\": 30,\n"
            "      \"worst_lateness_s\": 0.123457,\n      \"undecodable\": {\n        \"plant/cmd\": 7\n      }\n    },\n"
            "    \"control\": {\n      \"reported\": false\n    }\n"
            "  },\n"
            "  \"inputs\": {\n"
            "    \"evaluator\": {\n      \"plant/state\": {\n        \"accepted\": 5,\n        \"rejected\": {},\n"
            "        \"adjusted\": {}\n      }\n    },\n"
            "    \"plant\": {\n      \"plant/cmd\": {\n        \"accepted\": 998,\n        \"rejected\": {\n"
            "          \"non_finite\": 3\n        },\n        \"adjusted\": {\n          \"saturated\": 2\n        }\n"
            "      }\n    }\n"
            "  }\n"
            "}\n")
      << text;
}

}  // namespace
}  // namespace robodds::evaluator
