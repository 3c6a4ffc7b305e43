#pragma once
// Every parameter of the mission_source component.
// config/mission_source.params.yaml is generated from the table.

#include <cstdint>
#include <string>
#include <vector>

#include "common/param_table.hpp"

namespace robodds::mission_source {

// Units, ranges and one-line descriptions of these fields: mission_source_param_table() in
// mission_source_params.cpp (the one source; `robodds components --params mission_source` prints
// it). Defaults: the member initialisers.
struct MissionParams {
  /// The paper-1 mission.
  std::vector<params::Point2> waypoints{{60, 20}, {75, 15}, {90, 25}, {85, 40}, {70, 45}, {60, 55},
                                        {75, 65}, {90, 70}, {85, 85}, {70, 90}, {55, 80}, {40, 90},
                                        {25, 85}, {15, 70}, {25, 55}, {40, 50}, {30, 35}, {20, 20}};
};

const params::ParamTable<MissionParams>& mission_source_param_table();

}  // namespace robodds::mission_source
