#pragma once
// Every parameter of the replay_source component.
// config/replay_source.params.yaml is generated from the table.

#include <string>
#include <vector>

#include "common/param_table.hpp"

namespace robodds::replay_source {

// Units, ranges and one-line descriptions of these fields: replay_source_param_table() in
// replay_source_params.cpp (the one source). Defaults: the member initialisers.
struct ReplaySourceParams {
  std::string file;                 // the MCAP recording; empty: not set (a ConfigError)
  std::vector<std::string> topics;  // the topics it publishes from it; empty: not set (a ConfigError)
};

const params::ParamTable<ReplaySourceParams>& replay_source_param_table();

}  // namespace robodds::replay_source
