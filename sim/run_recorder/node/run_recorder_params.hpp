#pragma once
// Every parameter of the run_recorder component.
// config/run_recorder.params.yaml is generated from the table.

#include <string>
#include <vector>

#include "common/param_table.hpp"

namespace robodds::run_recorder {

// Units, ranges and one-line descriptions of these fields: run_recorder_param_table() in
// run_recorder_params.cpp (the one source; `robodds components --params run_recorder` prints it).
struct RunRecorderParams {
  std::string file;                 // empty: records nothing
  std::string compression = "zstd";
  std::vector<std::string> topics;  // empty: every topic the scenario's components publish
  double chunk_kb = 1024.0;
  bool foxglove_scene = false;
};

const params::ParamTable<RunRecorderParams>& run_recorder_param_table();

}  // namespace robodds::run_recorder
