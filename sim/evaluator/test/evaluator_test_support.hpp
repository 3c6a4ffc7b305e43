#pragma once
// What the evaluator's node tests share: the component registered on the harness and the text of
// its output files.

#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/component/registry.hpp"
#include "runtime/testing/node_harness.hpp"

ROBODDS_DECLARE_COMPONENT(evaluator);

namespace robodds::evaluator::testing {

/// Two robots, the evaluator recording plant/state from the start: 11 steps of 0.01 s.
inline const char* const kTwoRobotScenario = R"(name: evaluator_node
description: two robots, "quoted"
step_s: 0.01
duration_s: 0.1
seed: 1
robots:
  - {id: 1}
  - {id: 2}
components:
  - {name: evaluator, type: evaluator, params: {topics: [plant/state], metrics_after_s: 0.0}}
)";

inline void add_evaluator(robodds::testing::NodeHarness& h) {
  robodds::component_registration::register_evaluator(h.registry());
}

inline std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
  }
  return lines;
}

inline std::string text_of(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The number after "key": in `summary` (NaN if absent).
inline double summary_value(const std::string& summary, const std::string& key) {
  std::smatch m;
  const std::regex pattern("\"" + key + "\": ?(-?[0-9.eE+-]+)");
  return std::regex_search(summary, m, pattern) ? std::stod(m[1].str()) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace robodds::evaluator::testing
